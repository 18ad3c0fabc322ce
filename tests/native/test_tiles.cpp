// SPDX-License-Identifier: GPL-3.0-or-later
// The sparse, tiled result: every method cut into small tiles (the tile_size option) sets
// exactly the voxels it sets untiled, on the shared meshes and on faces lying exactly on
// tile borders; huge grids of small surfaces run within a small memory budget and are exact
// against the plane's own inequality; runs whose surface cannot fit are refused up front.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "hyvox/sparse_grid.h"
#include "hyvox/voxelize.h"
#include "support/mesh_arrays.h"
#include "support/test_mesh_loader.h"
#include "support/voxel_checks.h"

namespace hyvox {
namespace {

constexpr Method kTiledMethods[] = {Method::Cpu, Method::Reference, Method::Triangle, Method::Fragment, Method::Hybrid};

VoxelizeOptions optionsFor(Method method, Mode mode, int resolution, int tile_size) {
    VoxelizeOptions o;
    o.method = method;
    o.mode = mode;
    o.grid.resolution = resolution;
    o.hybrid.cutoff = 4.0;
    o.tile_size = tile_size;
    return o;
}

// Tiled and untiled runs of one method: the same voxels, and the tiled one really tiled.
void expectTilingChangesNothing(const MeshView& mesh, Method method, Mode mode, int resolution, int tile_size) {
    SCOPED_TRACE(std::string(toString(method)) + " " + toString(mode) + " @" + std::to_string(resolution) + " tile " +
                 std::to_string(tile_size));
    const VoxelizeResult whole = voxelize(mesh, optionsFor(method, mode, resolution, 0));
    const VoxelizeResult tiled = voxelize(mesh, optionsFor(method, mode, resolution, tile_size));
    EXPECT_EQ(whole.stats.tiles, 1u);
    EXPECT_GT(tiled.stats.tiles, 1u);
    EXPECT_GT(whole.stats.voxel_count, 0u);
    EXPECT_EQ(tiled.stats.voxel_count, whole.stats.voxel_count);
    EXPECT_TRUE(tiled.occupancy == whole.occupancy);
    EXPECT_EQ(tiled.stats.leaves, whole.occupancy.leafCount());
}

class TiledMeshTest : public ::testing::TestWithParam<std::string> {};

TEST_P(TiledMeshTest, EveryMethodSetsTheSameVoxelsInSmallTiles) {
    const test::TestMesh mesh = test::loadTestMesh(test::meshPath(GetParam()));
    for (Method method : kTiledMethods)
        for (Mode mode : {Mode::Conservative, Mode::Thin}) {
            if (method == Method::Reference && mode == Mode::Thin) continue;  // cpu thin is the thin oracle
            expectTilingChangesNothing(mesh.view(), method, mode, 48, 16);
        }
    // The tessellation too (PN-triangles: points off the flat triangles, binned by their reach):
    // the same points land in the same voxels, so bits and counts agree.
    VoxelizeOptions tess = optionsFor(Method::Tessellation, Mode::Conservative, 48, 0);
    tess.tessellation.pn_triangles = true;
    const VoxelizeResult tess_whole = voxelize(mesh.view(), tess);
    tess.tile_size = 16;
    const VoxelizeResult tess_tiled = voxelize(mesh.view(), tess);
    EXPECT_GT(tess_tiled.stats.tiles, 1u);
    EXPECT_TRUE(tess_tiled.occupancy == tess_whole.occupancy);
    auto key = [](const VoxelCount& c) { return std::make_tuple(c.i, c.j, c.k, c.count); };
    auto sortedCounts = [&](std::vector<VoxelCount> counts) {
        std::sort(counts.begin(), counts.end(), [&](const auto& a, const auto& b) { return key(a) < key(b); });
        std::vector<std::tuple<int, int, int, std::uint32_t>> out;
        for (const auto& c : counts) out.push_back(key(c));
        return out;
    };
    EXPECT_EQ(sortedCounts(tess_tiled.counts), sortedCounts(tess_whole.counts));
    for (const VoxelizeResult* r : {&tess_whole, &tess_tiled}) {
        std::uint64_t landed = 0;
        for (const auto& c : r->counts) landed += c.count;
        EXPECT_EQ(landed, r->stats.tessellation->points - r->stats.tessellation->points_clipped);
    }
    // And the tiled cpu run is the oracle's set (up to touches), so tile borders drop nothing.
    const VoxelizeResult tiled = voxelize(mesh.view(), optionsFor(Method::Cpu, Mode::Conservative, 48, 24));
    const VoxelizeResult oracle = voxelize(mesh.view(), optionsFor(Method::Reference, Mode::Conservative, 48, 0));
    test::expectMatchesOracle(test::compareResults(mesh.view(), Mode::Conservative, tiled, oracle));
}

INSTANTIATE_TEST_SUITE_P(SharedMeshes, TiledMeshTest, ::testing::ValuesIn(test::sharedMeshFiles()),
                         [](const ::testing::TestParamInfo<std::string>& mesh_case) {
                             return test::meshCaseName(mesh_case.param, 48);
                         });

// Two squares lying exactly on voxel planes that are tile borders (z = 16, x = 8): their
// voxels on both sides of the plane belong to different tiles.
TEST(Tiles, FacesOnTileBordersMarkBothSides) {
    const std::vector<float> positions = {2, 2, 16, 30, 2,  16, 30, 30, 16, 2, 30, 16,
                                          8, 3, 3,  8,  29, 3,  8,  29, 29, 8, 3,  29};
    const std::vector<std::uint32_t> triangles = {0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7};
    const MeshView mesh = test::viewOf(positions, triangles);
    for (Method method : kTiledMethods) {
        VoxelizeOptions o = optionsFor(method, Mode::Conservative, 32, 0);  // the voxel size wins
        o.grid.voxel_size = 1.0;
        o.grid.origin = std::array<double, 3>{0, 0, 0};
        o.grid.bounds = Bounds{{0, 0, 0}, {32, 32, 32}};
        const VoxelizeResult whole = voxelize(mesh, o);
        o.tile_size = 8;
        const VoxelizeResult tiled = voxelize(mesh, o);
        SCOPED_TRACE(toString(method));
        // Only tiles some triangle's candidates reach run: the horizontal square's (x, y tiles
        // 0-3, z tiles 1-2) and the vertical one's (x tiles 0-1, y and z tiles 0-3), 48 in all.
        EXPECT_EQ(tiled.stats.tiles, 48u);
        EXPECT_TRUE(tiled.occupancy == whole.occupancy);
        // The horizontal square covers x, y in [2, 30]: voxels 1..30 on both sides of z = 16.
        for (int i = 1; i <= 30; ++i)
            for (int j = 1; j <= 30; ++j) {
                ASSERT_TRUE(tiled.occupancy.test(i, j, 15)) << i << "," << j;
                ASSERT_TRUE(tiled.occupancy.test(i, j, 16)) << i << "," << j;
                ASSERT_FALSE(tiled.occupancy.test(i, j, 17) && (i < 7 || i > 8)) << i << "," << j;
            }
        // The vertical square at x = 8: voxels 7 (tile 0) and 8 (tile 1).
        for (int j = 2; j <= 29; ++j) {
            ASSERT_TRUE(tiled.occupancy.test(7, j, 20));
            ASSERT_TRUE(tiled.occupancy.test(8, j, 20));
        }
    }
}

// One large right triangle in the plane z = 0.5 of a 16384 x 16384 x 1 grid of unit voxels.
// Voxel (i, j, 0)'s closed box meets {x, y >= 0, x + y <= 16384} exactly when i + j <= 16384.
struct Plate {
    std::vector<float> positions{0, 0, 0.5f, 16384, 0, 0.5f, 0, 16384, 0.5f};
    std::vector<std::uint32_t> triangles{0, 1, 2};
    MeshView view() const { return test::viewOf(positions, triangles); }
    static VoxelizeOptions options(std::uint64_t budget_mib) {
        VoxelizeOptions o;
        o.grid.voxel_size = 1.0;
        o.grid.origin = std::array<double, 3>{0, 0, 0};
        o.grid.bounds = Bounds{{0, 0, 0}, {16384, 16384, 1}};
        o.memory_budget_mib = budget_mib;
        return o;
    }
};

TEST(Tiles, A16384WidePlateRunsInASmallBudgetAndIsExact) {
    const Plate plate;
    // 1.5 GiB: the estimate counts the .vdb a front door writes of its 2 M leaves (about 1.1 GiB);
    // tiles of 4096 (16 of them) as a small budget would make.
    VoxelizeOptions o = Plate::options(1536);
    o.tile_size = 4096;
    const VoxelizeResult r = voxelize(plate.view(), o);
    ASSERT_EQ(r.grid.dims, (std::array<std::int32_t, 3>{16384, 16384, 1}));
    EXPECT_GT(r.stats.tiles, 1u);
    // sum over i of the j in [0, min(16383, 16384 - i)]
    std::uint64_t expected = 0;
    for (std::uint64_t i = 0; i < 16384; ++i) expected += std::min<std::uint64_t>(16384, 16385 - i);
    EXPECT_EQ(r.stats.voxel_count, expected);
    EXPECT_LE(r.occupancy.byteSize(), 512ull << 20);
    std::mt19937 rng(5);
    std::uniform_int_distribution<int> coordinate(0, 16383);
    for (int n = 0; n < 20000; ++n) {
        const int i = coordinate(rng), j = coordinate(rng);
        ASSERT_EQ(r.occupancy.test(i, j, 0), i + j <= 16384) << i << "," << j;
    }
}

TEST(Tiles, ASurfaceThatCannotFitIsRefusedBeforeTheWork) {
    const Plate plate;
    try {
        voxelize(plate.view(), Plate::options(16));
        FAIL() << "expected ResourceError";
    } catch (const ResourceError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("needs about"), std::string::npos) << what;
        EXPECT_NE(what.find("memory budget of 16 MiB"), std::string::npos) << what;
    }
}

TEST(SparseGrid, TilesInAnyOrderGiveTheDenseGridsLeaves) {
    BitGrid dense({40, 24, 17});
    std::mt19937 rng(3);
    std::bernoulli_distribution on(0.03);
    for (int i = 0; i < 40; ++i)
        for (int j = 0; j < 24; ++j)
            for (int k = 0; k < 17; ++k)
                if (on(rng)) dense.set(i, j, k);
    SparseGrid tiled({40, 24, 17});
    for (int x0 : {32, 0, 16})  // out of order on purpose
        for (int y0 : {0, 16})
            for (int z0 : {16, 0}) {
                const std::array<std::int32_t, 3> dims{std::min(16, 40 - x0), std::min(16, 24 - y0),
                                                       std::min(16, 17 - z0)};
                BitGrid tile(dims);
                for (int i = 0; i < dims[0]; ++i)
                    for (int j = 0; j < dims[1]; ++j)
                        for (int k = 0; k < dims[2]; ++k)
                            if (dense.test(x0 + i, y0 + j, z0 + k)) tile.set(i, j, k);
                tiled.addTile(tile, {x0, y0, z0});
            }
    tiled.finish();
    EXPECT_EQ(tiled.count(), dense.count());
    EXPECT_TRUE(tiled.toBitGrid() == dense);
    EXPECT_TRUE(tiled == SparseGrid::fromBitGrid(dense));
    auto coords = tiled.coords(), expected = dense.coords();
    std::sort(coords.begin(), coords.end());
    std::sort(expected.begin(), expected.end());
    EXPECT_EQ(coords, expected);
}

}  // namespace
}  // namespace hyvox

namespace hyvox {
namespace {

// Displacement moves points up to strength x the largest height away from their triangle: a
// ramp lifts a flat square by up to 12 voxels across tile borders along z.
TEST(Tiles, DisplacedPointsLandInTheirTile) {
    const std::vector<float> positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    const std::vector<std::uint32_t> triangles = {0, 1, 2, 0, 2, 3};
    const std::vector<float> uvs = {0, 0, 1, 0, 1, 1, 0, 1};
    MeshView mesh = test::viewOf(positions, triangles);
    mesh.uvs = uvs.data();
    VoxelizeOptions o = optionsFor(Method::Tessellation, Mode::Conservative, 32, 0);
    o.grid.bounds = Bounds{{0, 0, -0.5}, {1, 1, 0.5}};
    o.tessellation.displacement_pixels.width = 8;
    o.tessellation.displacement_pixels.height = 8;
    for (int row = 0; row < 8; ++row)
        for (int col = 0; col < 8; ++col) o.tessellation.displacement_pixels.values.push_back(float(col) / 7.0f);
    o.tessellation.displacement_strength = 0.4;  // 12.8 voxels at u = 1
    o.tessellation.displacement_midlevel = 0.0;
    const VoxelizeResult whole = voxelize(mesh, o);
    o.tile_size = 8;
    const VoxelizeResult tiled = voxelize(mesh, o);
    EXPECT_GT(tiled.stats.tiles, 4u);
    EXPECT_TRUE(tiled.occupancy == whole.occupancy);
    EXPECT_EQ(tiled.stats.voxel_count, whole.stats.voxel_count);
    // The ramp reaches well into the upper tiles (z = 16 is the grid's middle plane).
    int top = 0;
    for (const auto& c : whole.occupancy.coords()) top = std::max(top, c[2]);
    EXPECT_GE(top, 16 + 10);
}

}  // namespace
}  // namespace hyvox
