// SPDX-License-Identifier: GPL-3.0-or-later
// The boxes of a region job (hyvox/region.h): for grids of every shape, the N boxes of the
// grid cover each of its voxels exactly once, run along its longest side, start on a leaf
// boundary, hold at least one leaf each, and differ by at most one leaf; more regions than
// leaves are refused, as is region text that is not K/N.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "hyvox/errors.h"
#include "hyvox/region.h"

namespace {

TEST(RegionBox, TheBoxesCutTheGridIntoLeavesAlongItsLongestSide) {
    std::mt19937 rng(3);
    std::uniform_int_distribution<int> side(1, 300);
    for (int trial = 0; trial < 200; ++trial) {
        hyvox::GridSpec grid;
        grid.dims = {side(rng), side(rng), side(rng)};
        const int axis = int(std::max_element(grid.dims.begin(), grid.dims.end()) - grid.dims.begin());
        const int leaves = (grid.dims[axis] + 7) / 8;
        for (int count : {1, 2, 3, 4, 7, leaves}) {
            if (count > leaves) continue;
            std::vector<int> owner(std::size_t(grid.dims[axis]), -1);
            int fewest = leaves, most = 0;
            for (int index = 0; index < count; ++index) {
                const hyvox::RegionBox box = hyvox::regionBox(grid, {index, count});
                ASSERT_EQ(box.axis, axis);
                for (int a = 0; a < 3; ++a) {
                    if (a == axis) continue;
                    ASSERT_EQ(box.lo[a], 0);
                    ASSERT_EQ(box.hi[a], grid.dims[a]);
                }
                ASSERT_EQ(box.lo[axis] % 8, 0);
                ASSERT_TRUE(box.hi[axis] % 8 == 0 || box.hi[axis] == grid.dims[axis]);
                ASSERT_LT(box.lo[axis], box.hi[axis]);
                for (int v = box.lo[axis]; v < box.hi[axis]; ++v) {
                    ASSERT_EQ(owner[std::size_t(v)], -1) << "voxel " << v << " in two boxes";
                    owner[std::size_t(v)] = index;
                }
                const int held = (box.hi[axis] - box.lo[axis] + 7) / 8;
                fewest = std::min(fewest, held);
                most = std::max(most, held);
            }
            ASSERT_TRUE(std::all_of(owner.begin(), owner.end(), [](int o) { return o >= 0; })) << "a voxel in no box";
            ASSERT_TRUE(std::is_sorted(owner.begin(), owner.end()));  // K runs along the axis
            ASSERT_LE(most - fewest, 1);
        }
        EXPECT_THROW(hyvox::regionBox(grid, {0, leaves + 1}), hyvox::InvalidInput);
    }
}

TEST(RegionBox, TheTextIsKOverN) {
    EXPECT_EQ(hyvox::parseRegion("2/5").index, 2);
    EXPECT_EQ(hyvox::parseRegion("2/5").count, 5);
    EXPECT_TRUE(hyvox::parseRegion("").whole());
    EXPECT_TRUE(hyvox::parseRegion("0/1").whole());
    EXPECT_EQ(hyvox::formatRegion(hyvox::parseRegion("0/1")), "");
    EXPECT_EQ(hyvox::formatRegion({3, 2048}), "3/2048");
    for (const char* bad : {"5/5", "1/2049", "1", "/2", "1/", "-1/2", "1/+2", "a/b", "1/2/3", "1 /2", "99999/100000"})
        EXPECT_THROW(hyvox::parseRegion(bad), hyvox::InvalidInput) << bad;
}

}  // namespace
