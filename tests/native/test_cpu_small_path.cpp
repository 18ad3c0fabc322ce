// SPDX-License-Identifier: GPL-3.0-or-later
// The cpu method decides a triangle with at most 4 candidate voxels along every axis in vector
// lanes (cpu/rasterize_small.cpp) and marks its voxels a grid word at a time. That path must
// set exactly the voxels the general row loops (cpu/rasterize_triangle.h) set for the same
// setup, voxel for voxel, for every size of candidate box, on and beside voxel planes, and
// across brick borders; and a soup of such triangles the brute-force reference's voxels.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <set>

#include "cpu/mark_voxels.h"
#include "cpu/rasterize_small.h"
#include "cpu/rasterize_triangle.h"
#include "cpu/triangle_setup.h"
#include "hyvox/bit_grid.h"
#include "support/triangle_soup.h"
#include "support/voxel_checks.h"

namespace hyvox::test {
namespace {

// A coordinate near `base + spread * u` (u uniform in [0, 1)): sometimes exactly on a voxel
// plane, on a voxel centre, or one double step beside a plane, where rounding decides.
double coordinate(std::mt19937& random, double base, double spread) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const double x = base + spread * unit(random);
    switch (random() % 8u) {
        case 0: return std::round(x);
        case 1: return std::floor(x) + 0.5;
        case 2: return std::nextafter(std::round(x), -1e9);
        case 3: return std::nextafter(std::round(x), 1e9);
        default: return x;
    }
}

std::array<std::array<double, 3>, 3> smallTriangle(std::mt19937& random, const std::array<int, 3>& tile_dims) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const double spread = 0.2 + 3.0 * unit(random);
    std::array<double, 3> base;
    for (int a = 0; a < 3; ++a) base[a] = 2.0 + (tile_dims[a] - 8.0) * unit(random);
    std::array<std::array<double, 3>, 3> c;
    for (auto& corner : c)
        for (int a = 0; a < 3; ++a) corner[a] = coordinate(random, base[a], spread);
    return c;
}

void rasterizeRowsAnyAxis(const cpu::TriangleSetup& t, cpu::WordMarker& marker) {
    switch (t.w) {
        case 0: cpu::rasterizeRows<0>(t, t.lo[1], t.hi[1] + 1, marker); break;
        case 1: cpu::rasterizeRows<1>(t, t.lo[1], t.hi[1] + 1, marker); break;
        default: cpu::rasterizeRows<2>(t, t.lo[1], t.hi[1] + 1, marker); break;
    }
}

TEST(CpuSmallPath, EqualsTheRowLoops) {
    // A tile of 29 x 30 x 31 voxels starting at (8, 16, 24): bricks of 8 cut it at 3 places
    // per axis, and partial bricks at its far sides.
    const std::array<int, 3> dims{29, 30, 31}, offset{8, 16, 24};
    const std::array<int, 3> clip_hi{offset[0] + dims[0] - 1, offset[1] + dims[1] - 1, offset[2] + dims[2] - 1};
    std::mt19937 random(23);
    std::set<int> sizes_seen;  // smallBoxBit of (sizes - 1)
    int tested = 0, with_voxels = 0, across_bricks = 0;
    for (Mode mode : {Mode::Conservative, Mode::Thin})
        for (int n = 0; n < 40000; ++n) {
            auto c = smallTriangle(random, dims);
            for (auto& corner : c)
                for (int a = 0; a < 3; ++a) corner[a] += offset[a];
            cpu::TriangleSetup t;
            if (cpu::setupTriangle(c, mode, offset, clip_hi, t) != cpu::SetupKind::Full || !cpu::fitsSmallPath(t))
                continue;
            BitGrid small(dims), rows(dims);
            {
                cpu::WordMarker marker(small, offset);
                cpu::rasterizeSmall(t, marker);
            }
            {
                cpu::WordMarker marker(rows, offset);
                rasterizeRowsAnyAxis(t, marker);
            }
            ASSERT_TRUE(small == rows) << toString(mode) << " triangle (" << c[0][0] << ", " << c[0][1] << ", "
                                       << c[0][2] << ") (" << c[1][0] << ", " << c[1][1] << ", " << c[1][2] << ") ("
                                       << c[2][0] << ", " << c[2][1] << ", " << c[2][2] << ")";
            ++tested;
            with_voxels += rows.count() > 0;
            sizes_seen.insert(cpu::smallBoxBit(t.hi[0] - t.lo[0], t.hi[1] - t.lo[1], t.hi[2] - t.lo[2]));
            bool crosses = false;
            for (int a = 0; a < 3; ++a) crosses |= (t.lo[a] >> 3) != (t.hi[a] >> 3);
            across_bricks += crosses;
        }
    std::printf("%d small triangles (%d with voxels, %d across bricks), %zu of 64 box sizes\n", tested, with_voxels,
                across_bricks, sizes_seen.size());
    // Every box size NU x NV x NW (swizzled: NW along the dominant normal axis) from 1 x 1 x 1
    // to 4 x 4 x 4 was exercised, but those deep along the normal's axis that a triangle can
    // reach only as a sliver along a diagonal (NW > 2 and NW > min(NU, NV)); and both ways of
    // marking.
    for (int nu = 1; nu <= 4; ++nu)
        for (int nv = 1; nv <= 4; ++nv)
            for (int nw = 1; nw <= 4; ++nw)
                if (nw <= 2 || nw <= std::min(nu, nv)) {
                    EXPECT_EQ(sizes_seen.count(cpu::smallBoxBit(nu - 1, nv - 1, nw - 1)), 1u)
                        << nu << " x " << nv << " x " << nw;
                }
    EXPECT_GT(with_voxels, 10000);
    EXPECT_GT(across_bricks, 1000);
}

TEST(CpuSmallPath, SoupEqualsReference) {
    std::mt19937 random(29);
    TriangleSoup soup;
    for (int n = 0; n < 3000; ++n) {
        const auto c = smallTriangle(random, {24, 24, 24});
        soup.add(c[0], c[1], c[2]);
    }
    for (Mode mode : {Mode::Conservative, Mode::Thin}) {
        VoxelizeOptions options;
        options.grid = unitGrid(24);
        options.mode = mode;
        const Comparison cmp = compareWithReference(soup.view(), options);
        std::printf("small soup %s: %s\n", toString(mode), cmp.summary().c_str());
        expectMatchesOracle(cmp);
    }
}

}  // namespace
}  // namespace hyvox::test
