// SPDX-License-Identifier: GPL-3.0-or-later
// Thin (6-separating) output of a closed mesh must separate inside from outside: no
// 6-connected path of empty voxels joins a voxel whose centre is inside the mesh (ray
// parity, an oracle independent of both voxelizers) to the grid boundary.
#include <gtest/gtest.h>

#include <string>
#include <tuple>

#include "support/test_mesh_loader.h"
#include "support/triangle_soup.h"
#include "support/voxel_checks.h"

namespace hyvox::test {
namespace {

class ThinSeparates : public ::testing::TestWithParam<std::tuple<std::string, int>> {};

TEST_P(ThinSeparates, InsideIsNotReachedFromTheBoundary) {
    const auto& [file, resolution] = GetParam();
    const TestMesh mesh = loadTestMesh(meshPath(file));
    VoxelizeOptions options;
    options.grid.resolution = resolution;
    options.grid.padding = 1;  // an empty layer all around, so the outside is connected
    options.mode = Mode::Thin;
    const VoxelizeResult result = voxelize(mesh.view(), options);
    const Separation s = expectSixSeparating(mesh.view(), result);
    std::printf("[ separate ] %s @%d thin: %llu voxels, %llu empty reached, %llu empty inside, %llu inside reached\n",
                file.c_str(), resolution, static_cast<unsigned long long>(result.stats.voxel_count),
                static_cast<unsigned long long>(s.reached), static_cast<unsigned long long>(s.inside_empty),
                static_cast<unsigned long long>(s.inside_reached));
}

INSTANTIATE_TEST_SUITE_P(WatertightMeshes, ThinSeparates,
                         ::testing::Values(std::tuple{"spot_vcolor.ply", 64}, std::tuple{"spot_vcolor.ply", 128},
                                           std::tuple{"armadillo_52k.ply", 128},
                                           std::tuple{"happy_buddha_100k.ply", 128},
                                           std::tuple{"igea_cyberware_268k.ply.gz", 96}));

TEST(ThinSeparation, UnitCube) {
    TriangleSoup cube;
    cube.addBox({0, 0, 0}, {1, 1, 1});
    VoxelizeOptions options;
    options.grid.resolution = 10;
    options.grid.padding = 1;
    options.mode = Mode::Thin;
    const VoxelizeResult result = voxelize(cube.view(), options);
    // Faces on voxel planes with padding 1 mark the whole boundary layer, so nothing is
    // reached from it: expectSixSeparating's reached > 0 does not apply here.
    const Separation s = floodFromBoundary(result.occupancy.toBitGrid(), insideByParity(cube.view(), result.grid));
    EXPECT_EQ(s.inside_reached, 0u);
    EXPECT_GT(s.inside_empty, 0u);
}

}  // namespace
}  // namespace hyvox::test
