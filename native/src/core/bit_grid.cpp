// SPDX-License-Identifier: GPL-3.0-or-later
#include "hyvox/bit_grid.h"

#include <stdexcept>

namespace hyvox {

BitGrid::BitGrid(std::array<std::int32_t, 3> dims) : dims_(dims), bricks_(BrickLayout::over(dims)) {
    for (int a = 0; a < 3; ++a)
        if (dims[a] < 1) throw std::invalid_argument("BitGrid dimensions must be positive");
    words_.resize(brickCount() * kWordsPerBrick);  // zero: see ZeroPageAllocator
}

std::uint64_t BitGrid::count() const {
    std::uint64_t total = 0;
    for (std::uint64_t w : words_) total += std::uint64_t(__builtin_popcountll(w));
    return total;
}

std::vector<std::array<std::int32_t, 3>> BitGrid::coords() const {
    std::vector<std::array<std::int32_t, 3>> out;
    out.reserve(count());
    const auto& n = bricks_.counts;
    for (std::int32_t bx = 0; bx < n[0]; ++bx)
        for (std::int32_t by = 0; by < n[1]; ++by)
            for (std::int32_t bz = 0; bz < n[2]; ++bz) {
                const std::size_t brick = bricks_.index(bx, by, bz);
                for (int x = 0; x < kWordsPerBrick; ++x) {
                    std::uint64_t word = words_[brick * kWordsPerBrick + x];
                    while (word) {
                        const int bit = __builtin_ctzll(word);
                        word &= word - 1;
                        out.push_back({bx * 8 + x, by * 8 + (bit >> 3), bz * 8 + (bit & 7)});
                    }
                }
            }
    return out;
}

}  // namespace hyvox
