// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The test oracle's triangle/voxel decisions, written plainly in double precision and
// sharing no code with the fast cpu backend.
//
// Everything here works in voxel space p' = (p - origin) / voxel_size, where voxel (i,j,k)
// is the closed box [i, i+1] x [j, j+1] x [k, k+1].
//   conservative (26-separating): the triangle meets the closed box (Akenine-Möller SAT,
//     13 axes).
//   thin (6-separating, Schwarz & Seidel 2010): the triangle's bounding box meets the
//     closed box, its plane meets the octahedron inscribed in the box (the "diamond" of
//     the JCGT paper's Fig. 2, right), and in each of the three coordinate planes the
//     three projected edge tests accept the inscribed 2D diamond (Fig. 3, right).
//   The normal is the cross product of the two shortest edges, as the cpu method computes
//     it (core/triangle_normal.h: a sliver keeps its plane, and every corner order gives it).
//   Planeless triangles (that normal is exactly zero: a segment or a point in voxel space, e.g. a needle whose
//     near corners coincide once the grid is applied) are what is left of them: conservative
//     needs nothing else (the SAT above is the segment's own test); thin replaces the plane
//     and winding tests by each projected edge's line against the diamond, on either side.
#include <array>
#include <cstdint>

#include "hyvox/grid.h"
#include "hyvox/mesh.h"
#include "hyvox/options.h"

namespace hyvox::reference {

using Vec3 = std::array<double, 3>;
using Triangle = std::array<Vec3, 3>;  // voxel-space corners
using Voxel = std::array<int, 3>;

// Voxel-space corners of triangle `index` of the mesh.
Triangle voxelSpaceTriangle(const ValidatedMesh& mesh, std::uint32_t index, const GridSpec& grid);

// The overlap decision for one voxel. `delta` grows (> 0) or shrinks (< 0) the voxel box
// (and, in thin mode, its inscribed octahedron and 2D diamonds) by that many voxel units
// on every side; delta = 0 is the oracle's own rule.
bool overlaps(const Triangle& triangle, const Voxel& voxel, Mode mode, double delta = 0.0);

// The candidate voxels of a triangle: every voxel whose box, grown by `delta`, meets the
// triangle's bounding box, clipped to the grid dims. Empty when lo > hi on some axis.
struct VoxelRange {
    Voxel lo{0, 0, 0};
    Voxel hi{-1, -1, -1};
    bool empty() const { return lo[0] > hi[0] || lo[1] > hi[1] || lo[2] > hi[2]; }
};
VoxelRange candidateVoxels(const Triangle& triangle, const std::array<std::int32_t, 3>& dims, double delta = 0.0);

}  // namespace hyvox::reference
