// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Oracle-side checks shared by the cpu voxelizer tests: equality with the brute-force
// reference up to proven touches, and the no-holes surface sampling.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "hyvox/voxelize.h"

namespace hyvox::test {

using Voxel = std::array<int, 3>;

struct Comparison {
    std::uint64_t cpu_voxels = 0, reference_voxels = 0;
    std::uint64_t cpu_only = 0, reference_only = 0;  // disagreements
    std::uint64_t touches = 0;                      // disagreements proven to be touches within eps
    std::vector<Voxel> unexplained;                 // disagreements that are not touches (must be empty)
    double cpu_ms = 0, reference_ms = 0, check_ms = 0;
    std::string summary() const;
};

// Runs `cpu` and `reference` with the same options (method ignored) and compares the
// voxel sets. Every disagreement is checked with the reference's eps-grown / eps-shrunk
// rule over all triangles: it is a touch iff some triangle meets the grown voxel and no
// triangle meets the shrunk one.
Comparison compareWithReference(const MeshView& mesh, VoxelizeOptions options, double eps = 1e-5);

// Dense samples on every usable triangle (a barycentric lattice with spacing <= 1/2 voxel,
// vertices and edges included); returns the number of samples (in voxel space) that lie in
// no closed box of a set voxel, up to `slack` voxel units for the samples' own rounding.
// `first_holes` receives up to 10 of them.
std::uint64_t countHoles(const MeshView& mesh, const VoxelizeResult& result, std::uint64_t* samples,
                         std::vector<std::array<double, 3>>* first_holes, double slack = 1e-9);

}  // namespace hyvox::test
