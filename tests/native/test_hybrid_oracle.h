// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Oracle checks for the GL methods: a result against an oracle's result (the `reference`
// in conservative mode, the `cpu` thin voxelizer in thin mode) where every disagreement
// must be a touch within eps (support/voxel_checks does the same for cpu vs reference
// only), and 6-separability of a thin voxelization of a closed mesh.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "hyvox/voxelize.h"

namespace hyvox::test {

struct OracleComparison {
    std::uint64_t result_voxels = 0, oracle_voxels = 0;
    std::uint64_t result_only = 0, oracle_only = 0;  // disagreements
    std::uint64_t touches = 0;                       // disagreements shown to be touches
    std::vector<std::array<int, 3>> unexplained;     // must be empty
    std::string summary() const;
};

OracleComparison compareToOracle(const MeshView& mesh, Mode mode, const VoxelizeResult& result,
                                 const VoxelizeResult& oracle, double eps = 1e-5);

// Empty voxels reachable from outside the grid through 6-connected empty voxels that have
// their centre inside the closed mesh (parity of crossings along +x); 0 = 6-separating.
// `inside` receives how many voxel centres lie inside (so a test can insist there are some).
std::uint64_t countSixLeaks(const MeshView& mesh, const VoxelizeResult& result, std::uint64_t* inside);

}  // namespace hyvox::test
