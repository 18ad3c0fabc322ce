// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Setting bits of the shared BitGrid from many threads without locks. Neighbouring small
// triangles mark the same voxels many times over, so a plain load first skips most of the
// locked read-modify-writes; bits of one column that share a 64-bit word are OR-ed at once.
// Voxels are given in grid coordinates; the bits are the tile's, which starts at `offset`
// (multiples of 8, so a voxel's place inside its brick is the same in both).
#include <array>
#include <cstdint>

#include "hyvox/bit_grid.h"

namespace hyvox::cpu {

class WordMarker {
public:
    WordMarker(BitGrid& grid, const std::array<std::int32_t, 3>& offset) : grid_(grid), offset_(offset) {}
    ~WordMarker() { flush(); }
    WordMarker(const WordMarker&) = delete;
    WordMarker& operator=(const WordMarker&) = delete;

    void mark(int i, int j, int k) {
        std::uint64_t* word = grid_.data() + grid_.wordIndex(i - offset_[0], j - offset_[1], k - offset_[2]);
        if (word != word_) {
            flush();
            word_ = word;
        }
        mask_ |= BitGrid::bitMask(j, k);
    }
    void flush() {
        if (word_ && (__atomic_load_n(word_, __ATOMIC_RELAXED) & mask_) != mask_)
            __atomic_fetch_or(word_, mask_, __ATOMIC_RELAXED);
        word_ = nullptr;
        mask_ = 0;
    }

private:
    BitGrid& grid_;
    std::array<std::int32_t, 3> offset_;
    std::uint64_t* word_ = nullptr;
    std::uint64_t mask_ = 0;
};

}  // namespace hyvox::cpu
