// SPDX-License-Identifier: GPL-3.0-or-later
// The cpu method skips a small triangle whose candidate voxels are all set already
// (cpu/mark_voxels.h: WordMarker::allMarked). The check itself against testing every voxel of
// the box, across brick borders and with a mark still pending in the marker; and meshes where
// most triangles are skipped: their voxels must be exactly the union of every triangle
// voxelized on its own (an empty grid each time, so nothing is skipped there), and the
// brute-force reference's.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "cpu/mark_voxels.h"
#include "hyvox/bit_grid.h"
#include "support/triangle_soup.h"
#include "support/voxel_checks.h"

namespace hyvox::test {
namespace {

bool everyVoxelSet(const BitGrid& grid, const std::array<int, 3>& offset, const std::array<int, 3>& lo,
                   const std::array<int, 3>& hi) {
    for (int i = lo[0]; i <= hi[0]; ++i)
        for (int j = lo[1]; j <= hi[1]; ++j)
            for (int k = lo[2]; k <= hi[2]; ++k)
                if (!grid.test(i - offset[0], j - offset[1], k - offset[2])) return false;
    return true;
}

TEST(CpuAlreadyCovered, AllMarkedEqualsTestingEveryVoxel) {
    // A tile of 37 x 29 x 41 voxels starting at (8, 16, 0): partial bricks at its far sides.
    const std::array<int, 3> dims{37, 29, 41}, offset{8, 16, 0};
    std::mt19937 random(17);
    int answered_true = 0, answered_false = 0;
    for (int round = 0; round < 40; ++round) {
        BitGrid grid(dims);
        // Filled boxes (so that "all set" happens), then a few holes punched at random.
        for (int box = 0; box < 60; ++box) {
            std::array<int, 3> lo, hi;
            for (int a = 0; a < 3; ++a) {
                lo[a] = int(random() % unsigned(dims[a]));
                hi[a] = std::min(dims[a] - 1, lo[a] + int(random() % 20u));
            }
            for (int i = lo[0]; i <= hi[0]; ++i)
                for (int j = lo[1]; j <= hi[1]; ++j)
                    for (int k = lo[2]; k <= hi[2]; ++k) grid.set(i, j, k);
        }
        for (int h = 0; h < 40; ++h) {
            const std::array<int, 3> v{int(random() % 37u), int(random() % 29u), int(random() % 41u)};
            grid.data()[grid.wordIndex(v[0], v[1], v[2])] &= ~BitGrid::bitMask(v[1], v[2]);
        }
        cpu::WordMarker marker(grid, offset);
        for (int query = 0; query < 400; ++query) {
            std::array<int, 3> lo, hi;  // grid coordinates, inside the tile, 1 to 10 voxels per axis
            for (int a = 0; a < 3; ++a) {
                const int size = 1 + int(random() % 10u);
                lo[a] = offset[a] + int(random() % unsigned(dims[a] - size + 1));
                hi[a] = lo[a] + size - 1;
            }
            if (query % 7 == 0) {
                // A mark still pending in the marker (not yet in the grid) counts as set.
                const std::array<int, 3> v{lo[0], hi[1], lo[2]};
                BitGrid copy = grid;
                marker.mark(v[0], v[1], v[2]);
                copy.set(v[0] - offset[0], v[1] - offset[1], v[2] - offset[2]);
                const bool expected = everyVoxelSet(copy, offset, lo, hi);
                EXPECT_EQ(marker.allMarked(lo, hi), expected);
                marker.flush();
                EXPECT_TRUE(grid == copy);
                (expected ? answered_true : answered_false) += 1;
                continue;
            }
            const bool expected = everyVoxelSet(grid, offset, lo, hi);
            EXPECT_EQ(marker.allMarked(lo, hi), expected)
                << "box " << lo[0] << "," << lo[1] << "," << lo[2] << " .. " << hi[0] << "," << hi[1] << "," << hi[2];
            (expected ? answered_true : answered_false) += 1;
        }
    }
    // Both answers were exercised, not only the easy one.
    EXPECT_GT(answered_true, 2000);
    EXPECT_GT(answered_false, 2000);
    std::printf("%d boxes all set, %d not\n", answered_true, answered_false);
}

// Sub-voxel triangles, many per voxel: a wavy sheet of (n x n) quads, `copies` times over
// with each copy shifted by a fraction of a voxel, as shared vertices (the integer first look)
// or as a soup (the per-corner setup).
struct Sheet {
    std::vector<float> positions;
    std::vector<std::uint32_t> triangles;
};

Sheet wavySheet(int n, double step, int copies, bool shared) {
    Sheet m;
    for (int copy = 0; copy < copies; ++copy) {
        auto point = [&](int i, int j) {
            return std::array<double, 3>{1.3 + i * step + 0.11 * copy, 1.1 + j * step,
                                         5.0 + 2.2 * std::sin(0.21 * i + copy) * std::cos(0.17 * j)};
        };
        const std::uint32_t base = std::uint32_t(m.positions.size() / 3);
        if (shared)
            for (int j = 0; j <= n; ++j)
                for (int i = 0; i <= n; ++i)
                    for (double c : point(i, j)) m.positions.push_back(float(c));
        auto corner = [&](int i, int j) {
            if (shared) return base + std::uint32_t(j * (n + 1) + i);
            for (double c : point(i, j)) m.positions.push_back(float(c));
            return std::uint32_t(m.positions.size() / 3 - 1);
        };
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i)
                for (const auto& tri : {std::array<std::array<int, 2>, 3>{{{i, j}, {i + 1, j}, {i + 1, j + 1}}},
                                        std::array<std::array<int, 2>, 3>{{{i, j}, {i + 1, j + 1}, {i, j + 1}}}})
                    for (const auto& c : tri) m.triangles.push_back(corner(c[0], c[1]));
    }
    return m;
}

VoxelizeOptions optionsFor(Mode mode, int threads) {
    VoxelizeOptions options;
    options.grid = unitGrid(12);
    options.mode = mode;
    options.method = Method::Cpu;
    options.threads = threads;
    return options;
}

TEST(CpuAlreadyCovered, SkippedTrianglesChangeNoVoxel) {
    for (bool shared : {true, false})
        for (Mode mode : {Mode::Conservative, Mode::Thin}) {
            const Sheet sheet = wavySheet(30, 0.3, 3, shared);
            const MeshView mesh = viewOf(sheet.positions, sheet.triangles);
            const VoxelizeResult all = voxelize(mesh, optionsFor(mode, 1));
            // Many triangles are skipped on this mesh (one thread: a fixed order).
            ASSERT_TRUE(all.stats.cpu.has_value());
            EXPECT_GT(all.stats.cpu->triangles_already_covered, sheet.triangles.size() / 3 / 10)
                << (shared ? "shared" : "soup") << " " << toString(mode);

            // The union of every triangle alone on the same grid.
            VoxelList expected;
            for (std::size_t t = 0; t < sheet.triangles.size(); t += 3) {
                const std::vector<std::uint32_t> one(sheet.triangles.begin() + std::ptrdiff_t(t),
                                                     sheet.triangles.begin() + std::ptrdiff_t(t) + 3);
                const VoxelizeResult alone = voxelize(viewOf(sheet.positions, one), optionsFor(mode, 1));
                EXPECT_EQ(alone.stats.cpu->triangles_already_covered, 0u);
                const VoxelList voxels = sortedVoxels(alone);
                expected.insert(expected.end(), voxels.begin(), voxels.end());
            }
            std::sort(expected.begin(), expected.end());
            expected.erase(std::unique(expected.begin(), expected.end()), expected.end());
            EXPECT_EQ(sortedVoxels(all), expected) << (shared ? "shared" : "soup") << " " << toString(mode);
            // Two threads skip other triangles, the voxels are the same.
            EXPECT_EQ(sortedVoxels(voxelize(mesh, optionsFor(mode, 2))), expected);

            VoxelizeOptions reference = optionsFor(mode, 1);
            reference.method = Method::Reference;
            const Comparison cmp = compareResults(mesh, mode, all, voxelize(mesh, reference));
            expectMatchesOracle(cmp);
        }
}

}  // namespace
}  // namespace hyvox::test
