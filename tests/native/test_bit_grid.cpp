// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <set>
#include <vector>

#include "hyvox/bit_grid.h"
#include "hyvox/zero_page_allocator.h"

namespace {

TEST(BitGrid, SetTestAndCoordsRoundTrip) {
    hyvox::BitGrid grid({19, 9, 33});
    const std::set<std::array<int, 3>> voxels{{0, 0, 0}, {18, 8, 32}, {7, 7, 7}, {8, 0, 1}, {3, 5, 17}};
    for (const auto& v : voxels) grid.set(v[0], v[1], v[2]);
    EXPECT_EQ(grid.count(), voxels.size());
    for (const auto& v : voxels) EXPECT_TRUE(grid.test(v[0], v[1], v[2]));
    EXPECT_FALSE(grid.test(1, 0, 0));
    std::set<std::array<int, 3>> back;
    for (const auto& c : grid.coords()) back.insert({c[0], c[1], c[2]});
    EXPECT_EQ(back, voxels);
}

TEST(BitGrid, LayoutMatchesOpenVdbLeafOffsets) {
    // OpenVDB LeafNode<T,3>::coordToOffset = (x&7)<<6 | (y&7)<<3 | (z&7), NodeMask word = n>>6.
    hyvox::BitGrid grid({16, 16, 16});
    grid.set(8 + 3, 5, 2);
    const std::size_t brick = (1 * 2 + 0) * 2 + 0;
    const int n = (3 << 6) | (5 << 3) | 2;
    EXPECT_EQ(grid.data()[brick * 8 + (n >> 6)], std::uint64_t(1) << (n & 63));
}

TEST(ZeroPageAllocator, ArraysAreZeroWritableToTheEndAndLargeOnesStartOnAHugePage) {
    // Sizes below, at and around the mapping threshold (1 MiB) and the huge page (2 MiB).
    for (const std::size_t count : {std::size_t(100), std::size_t(1) << 18, (std::size_t(1) << 18) + 3,
                                    std::size_t(1) << 19, (std::size_t(3) << 19) + 7}) {
        std::vector<std::uint32_t, hyvox::ZeroPageAllocator<std::uint32_t>> words(count);
        EXPECT_TRUE(std::all_of(words.begin(), words.end(), [](std::uint32_t w) { return w == 0; })) << count;
        if (count * sizeof(std::uint32_t) >= (std::size_t(1) << 20)) {
            EXPECT_EQ(reinterpret_cast<std::uintptr_t>(words.data()) % (std::uintptr_t(1) << 21), 0u) << count;
        }
        for (std::size_t i = 0; i < count; ++i) words[i] = std::uint32_t(i);  // every page is mapped
        EXPECT_EQ(words.back(), std::uint32_t(count - 1));
    }
}

}  // namespace
