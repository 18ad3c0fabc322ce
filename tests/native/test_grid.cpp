// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "hyvox/bit_grid.h"
#include "hyvox/errors.h"
#include "hyvox/grid.h"

namespace {

hyvox::Bounds box(double x0, double y0, double z0, double x1, double y1, double z1) {
    hyvox::Bounds b;
    b.min = {x0, y0, z0};
    b.max = {x1, y1, z1};
    return b;
}

TEST(Grid, ResolutionSpansTheLongestSide) {
    hyvox::GridOptions options;
    options.resolution = 64;
    const auto grid = hyvox::makeGrid(box(-1, 0, 2, 3, 1, 2.5), options);
    EXPECT_DOUBLE_EQ(grid.voxel_size, 4.0 / 64);
    EXPECT_EQ(grid.dims[0], 64);
    EXPECT_EQ(grid.dims[1], 16);
    EXPECT_EQ(grid.dims[2], 8);
    EXPECT_EQ(grid.origin[0], -1.0);
    EXPECT_EQ(grid.origin[2], 2.0);
}

TEST(Grid, FlatMeshGetsOneVoxelThickness) {
    hyvox::GridOptions options;
    options.resolution = 10;
    const auto grid = hyvox::makeGrid(box(0, 0, 0, 1, 1, 0), options);
    EXPECT_EQ(grid.dims[2], 1);
}

TEST(Grid, VoxelSizeOverridesResolutionAndCeilsDims) {
    hyvox::GridOptions options;
    options.voxel_size = 0.3;
    const auto grid = hyvox::makeGrid(box(0, 0, 0, 1, 0.6, 0.25), options);
    EXPECT_EQ(grid.dims[0], 4);  // ceil(3.33)
    EXPECT_EQ(grid.dims[2], 1);
}

TEST(Grid, ExactMultipleGetsExactlyThatManyVoxels) {
    hyvox::GridOptions options;
    options.voxel_size = 0.25;
    const auto grid = hyvox::makeGrid(box(0, 0, 0, 2, 2, 2), options);
    EXPECT_EQ(grid.dims[0], 8);
}

TEST(Grid, PaddingAddsVoxelsOnEverySide) {
    hyvox::GridOptions options;
    options.voxel_size = 1.0;
    options.padding = 2;
    const auto grid = hyvox::makeGrid(box(0, 0, 0, 4, 4, 4), options);
    EXPECT_EQ(grid.dims[0], 8);
    EXPECT_EQ(grid.origin[0], -2.0);
    const auto c = grid.voxelCentre(0, 0, 0);
    EXPECT_DOUBLE_EQ(c[0], -1.5);
}

TEST(Grid, OutOfRangeInputsAreClearErrors) {
    hyvox::GridOptions options;
    options.resolution = 0;
    EXPECT_THROW(hyvox::makeGrid(box(0, 0, 0, 1, 1, 1), options), hyvox::InvalidInput);
    options.resolution = hyvox::kMaxResolution + 1;
    EXPECT_THROW(hyvox::makeGrid(box(0, 0, 0, 1, 1, 1), options), hyvox::InvalidInput);
    options.resolution = 16;
    EXPECT_THROW(hyvox::makeGrid(box(0, 0, 0, 0, 0, 0), options), hyvox::InvalidInput);
    options.voxel_size = -1.0;
    EXPECT_THROW(hyvox::makeGrid(box(0, 0, 0, 1, 1, 1), options), hyvox::InvalidInput);
    options.voxel_size = 1e-9;  // far too many voxels
    EXPECT_THROW(hyvox::makeGrid(box(0, 0, 0, 1, 1, 1), options), hyvox::InvalidInput);
}

TEST(Grid, SpecFormulasFollowTheConvention) {
    hyvox::GridSpec grid;
    grid.origin = {-1, 2, 0.5};
    grid.voxel_size = 0.25;
    grid.dims = {17, 8, 9};
    EXPECT_EQ(grid.toVoxel(std::array<double, 3>{-1, 2, 0.5}), (std::array<double, 3>{0, 0, 0}));
    EXPECT_EQ(grid.toVoxel(std::array<float, 3>{0.0f, 2.5f, -0.25f}), (std::array<double, 3>{4, 2, -3}));
    EXPECT_EQ(grid.maxSide(), 17);
    EXPECT_EQ(grid.dimsText(), "17x8x9");
    // ceil(dims / 8) bricks, numbered with x slowest and z fastest.
    const hyvox::BrickLayout bricks = grid.bricks();
    EXPECT_EQ(bricks.counts, (std::array<std::int32_t, 3>{3, 1, 2}));
    EXPECT_EQ(bricks.total(), 6u);
    EXPECT_EQ(bricks.index(2, 0, 1), 5u);
    EXPECT_EQ(bricks.indexOfVoxel(16, 7, 8), 5u);
    EXPECT_EQ(bricks.indexOfVoxel(15, 7, 7), 2u);
    for (std::size_t b = 0; b < bricks.total(); ++b) {
        const auto at = bricks.at(b);
        EXPECT_EQ(bricks.index(at[0], at[1], at[2]), b);
    }
    EXPECT_EQ(hyvox::BitGrid(grid.dims).bricks().counts, bricks.counts);
}

// snap_origin against a brute-force oracle: the origin is k·s for a whole k (the very double
// k * s), at or below the bounds min and less than a voxel below it (up to the rounding of
// min / s: a quotient just under a whole number floors one lower). Sizes that divide
// decimals inexactly (0.1, 0.15) and minima on exact multiples included.
TEST(Grid, SnapOriginIsAWholeMultipleWithinAVoxelBelowTheMin) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> coordinate(-50.0, 50.0);
    std::uniform_int_distribution<int> step(-30, 30);
    for (const double s : {0.15, 0.1, 1e-3, 3.0, 0.3}) {
        for (int i = 0; i < 2000; ++i) {
            // Half on whole (or nearly whole) multiples, where the quotient rounds either way.
            const double x = i % 2 ? coordinate(rng) : step(rng) * s * (i % 4 ? 1.0 : 1.0 + 1e-16);
            hyvox::GridOptions options;
            options.voxel_size = s;
            options.snap_origin = true;
            const auto grid = hyvox::makeGrid(box(x, x, x, x + 1.0, x + 2.0, x + 3.0), options);
            for (int a = 0; a < 3; ++a) {
                const double origin = grid.origin[a];
                const double k = std::round(origin / s);
                ASSERT_EQ(origin, k * s) << "x " << x << " s " << s;
                ASSERT_LE(origin, x) << "x " << x << " s " << s;
                ASSERT_LE(x - origin, s * (1 + 1e-9)) << "x " << x << " s " << s;
                // The grid still reaches the bounds max, and not a voxel beyond (up to rounding).
                const double max = x + 1.0 + a, slack = 1e-12 * (1 + std::fabs(max));
                ASSERT_GE(origin + grid.dims[a] * s, max - slack);
                ASSERT_LT(origin + (grid.dims[a] - 1) * s, max + slack);
            }
        }
    }
}

TEST(Grid, SnapOriginKeepsAGivenOriginAndPadsAfterSnapping) {
    hyvox::GridOptions options;
    options.voxel_size = 0.5;
    options.snap_origin = true;
    options.origin = std::array<double, 3>{0.3, 0.3, 0.3};
    EXPECT_EQ(hyvox::makeGrid(box(0.3, 0.3, 0.3, 1, 1, 1), options).origin[0], 0.3);
    options.origin.reset();
    options.padding = 2;
    const auto grid = hyvox::makeGrid(box(0.7, -0.2, 1.0, 2, 2, 2), options);
    EXPECT_EQ(grid.origin[0], 0.5 - 2 * 0.5);
    EXPECT_EQ(grid.origin[1], -0.5 - 2 * 0.5);
    EXPECT_EQ(grid.origin[2], 1.0 - 2 * 0.5);
    EXPECT_EQ(grid.dims[0], 3 + 4);  // 0.5 .. 2.0
}

TEST(Grid, SnapOriginWithAResolutionSnapsToItsVoxelSize) {
    hyvox::GridOptions options;
    options.resolution = 4;
    options.snap_origin = true;
    const auto grid = hyvox::makeGrid(box(0.25, 0, 0, 2.25, 1, 1), options);
    EXPECT_EQ(grid.voxel_size, 0.5);
    EXPECT_EQ(grid.origin[0], 0.0);
    EXPECT_EQ(grid.dims[0], 5);  // 0 .. 2.5 covers 2.25
}

}  // namespace
