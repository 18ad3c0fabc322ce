// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Oracle-side checks shared by the voxelizer tests (cpu, GL, tessellation): equality of two
// voxel sets up to proven touches, the no-holes surface sampling, and 6-separation.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "hyvox/voxelize.h"
#include "reference/reference_overlap.h"

namespace hyvox::test {

using Voxel = std::array<int, 3>;

// How a voxel relates to a triangle within a tolerance, by the reference's overlap rule:
// `grown` = it overlaps the voxel grown by eps, `shrunk` = it overlaps the voxel shrunk by
// eps. A backend's answer for a voxel with grown && !shrunk is a "touch": either answer is
// right within eps.
struct Touch {
    bool grown = false;
    bool shrunk = false;
    bool isTouch() const { return grown && !shrunk; }
};
Touch overlapWithin(const reference::Triangle& triangle, const Voxel& voxel, Mode mode, double eps);

// Two voxelizations of one mesh on one grid, compared voxel by voxel. "result" is the set
// under test, "oracle" the one it must equal (the `reference` backend in conservative mode,
// the `cpu` thin voxelizer in thin mode, or any other trusted set).
struct Comparison {
    std::uint64_t result_voxels = 0, oracle_voxels = 0;
    std::uint64_t result_only = 0, oracle_only = 0;     // disagreements
    std::uint64_t touches = 0;                          // disagreements proven to be touches within eps
    std::vector<Voxel> unexplained;                     // disagreements that are not touches (must be empty)
    std::uint64_t unexplained_result_only = 0;          // of those, voxels only the result has
    double result_ms = 0, oracle_ms = 0, check_ms = 0;  // 0 where the caller ran the voxelizers
    std::string summary() const;
};

// Compares `result` with `oracle` (same grid, else std::invalid_argument). Every disagreement
// is checked with the reference's eps-grown / eps-shrunk rule for `mode` over all triangles
// (double precision): it is a touch iff some triangle meets the grown voxel and no triangle
// meets the shrunk one.
Comparison compareResults(const MeshView& mesh, Mode mode, const VoxelizeResult& result, const VoxelizeResult& oracle,
                          double eps = 1e-5);

// Runs `cpu` and `reference` with the same options (method ignored) and compares them
// (`cpu` is the result, `reference` the oracle; both timed).
Comparison compareWithReference(const MeshView& mesh, VoxelizeOptions options, double eps = 1e-5);

// The acceptance rule for a comparison (GoogleTest expectations): a non-empty oracle, no
// unexplained disagreement, and touches rare, at most max(10, oracle voxels / 10000), so a
// systematic shift cannot hide as "touches".
void expectMatchesOracle(const Comparison& cmp);

// Dense samples on every usable triangle (a barycentric lattice with spacing <= 1/2 voxel,
// vertices and edges included); returns the number of samples (in voxel space) that lie in
// no closed box of a set voxel, up to `slack` voxel units for the samples' own rounding.
// `first_holes` receives up to 10 of them.
std::uint64_t countHoles(const MeshView& mesh, const VoxelizeResult& result, std::uint64_t* samples,
                         std::vector<std::array<double, 3>>* first_holes, double slack = 1e-9);

// 6-separation of a closed mesh's thin voxelization, against ray parity (an oracle that
// shares nothing with the voxelizers):
// inside[(i*dy + j)*dz + k] says whether voxel (i,j,k)'s centre (nudged by far less than a
// voxel, to keep the rays off mesh edges) is inside the mesh, by the parity of a +x ray.
std::vector<char> insideByParity(const MeshView& mesh, const GridSpec& grid);

struct Separation {
    std::uint64_t reached = 0;         // empty voxels 6-connected to the grid boundary
    std::uint64_t inside_empty = 0;    // empty voxels with an inside centre
    std::uint64_t inside_reached = 0;  // ... that the flood reached: 0 = 6-separating
};

// Floods the empty voxels of `bits` from the grid's faces, 6-connected.
Separation floodFromBoundary(const BitGrid& bits, const std::vector<char>& inside);

// GoogleTest expectations that the thin voxelization `result` of the closed `mesh` (with an
// empty layer all around, e.g. padding 1) is 6-separating: the flood from the boundary
// reaches empty voxels, more than `min_inside_empty` empty voxels are inside, and none of
// them is reached. Negative control: with the slab x = dims/2 of the surface removed, the
// same check must find a leak (otherwise it would prove nothing). Returns the flood's counts.
Separation expectSixSeparating(const MeshView& mesh, const VoxelizeResult& result, std::uint64_t min_inside_empty = 0);

}  // namespace hyvox::test
