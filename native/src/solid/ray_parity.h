// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Ray parity: how many times the ray from a point straight down (-z) crosses the surface,
// modulo 2. Exact for closed meshes, including rays through shared edges and vertices:
// vertices are snapped to a fixed-point lattice of 2^-20 voxel (every triangle that shares a
// vertex sees the same snapped vertex), the point-in-projected-triangle tests are exact
// 128-bit integer orientations, and a point lying exactly on a projected edge is decided as
// if it were moved by (ε, ε²) (symbolic perturbation), the same for both triangles of an edge,
// so a closed surface's shared edge or vertex is crossed exactly once.
#include <array>
#include <cstdint>
#include <vector>

#include "hyvox/grid.h"
#include "hyvox/mesh.h"

namespace hyvox::solid {

class RayParity {
public:
    // Throws InvalidInput when a vertex lies more than 2^40 voxels from the grid.
    RayParity(const ValidatedMesh& mesh, const GridSpec& grid);
    // 1 when the ray from voxel (i,j,k)'s centre down crosses the surface an odd number of
    // times (the centre is inside), else 0. The centre must not lie on the surface.
    int at(int i, int j, int k) const;

private:
    struct Triangle {
        std::array<std::int64_t, 3> x, y;  // snapped xy of the corners
        std::array<double, 3> z;           // voxel-space z of the corners
        std::int64_t x_lo, x_hi, y_lo, y_hi;
    };
    std::array<std::int32_t, 2> columns_{0, 0};     // 8×8-ray columns along x and y
    std::vector<Triangle> triangles_;               // those whose projection is not a line
    std::vector<std::uint32_t> column_start_;       // CSR: triangles of column (cx, cy)
    std::vector<std::uint32_t> column_triangles_;
};

}  // namespace hyvox::solid
