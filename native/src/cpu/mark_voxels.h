// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Setting bits of the shared BitGrid from many threads without locks. Neighbouring small
// triangles mark the same voxels many times over, so a plain load first skips most of the
// locked read-modify-writes; bits of one column that share a 64-bit word are OR-ed at once.
// Voxels are given in grid coordinates; the bits are the tile's, which starts at `offset`
// (multiples of 8, so a voxel's place inside its brick is the same in both).
//
// allMarked() answers whether every voxel of a small box is set already: a triangle whose
// candidate voxels are all set can add nothing (marks only OR bits in), so the voxelizer skips
// its setup and tests. On a fine mesh most triangles lie where their neighbours have marked
// every voxel around them (docs/why/cpu-voxelize.md).
#include <algorithm>
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

    void mark(int i, int j, int k) { markWord(i, j, k, BitGrid::bitMask(j, k)); }
    // Marks the voxels of `mask` (BitGrid::bitMask bits) in the word that holds voxel (i, j, k).
    void markWord(int i, int j, int k, std::uint64_t mask) {
        std::uint64_t* word = grid_.data() + grid_.wordIndex(i - offset_[0], j - offset_[1], k - offset_[2]);
        if (word != word_) {
            flush();
            word_ = word;
        }
        mask_ |= mask;
    }
    void flush() {
        if (word_ && (__atomic_load_n(word_, __ATOMIC_RELAXED) & mask_) != mask_)
            __atomic_fetch_or(word_, mask_, __ATOMIC_RELAXED);
        word_ = nullptr;
        mask_ = 0;
    }

    // Whether every voxel of the box lo..hi (grid coordinates, inclusive, inside the tile) is
    // set, in the grid or in this marker's pending word. Bits
    // only ever turn on, so a set bit read while other threads mark stays true; a bit being
    // set meanwhile may read as clear, which only costs a skipped shortcut.
    bool allMarked(const std::array<int, 3>& lo, const std::array<int, 3>& hi) const {
        const int i0 = lo[0] - offset_[0], j0 = lo[1] - offset_[1], k0 = lo[2] - offset_[2];
        const int i1 = hi[0] - offset_[0], j1 = hi[1] - offset_[1], k1 = hi[2] - offset_[2];
        // Per brick along j and k, the box's part of each row i: one word and mask each.
        for (int jb = j0 >> 3; jb <= j1 >> 3; ++jb) {
            const int ja = std::max(j0, jb << 3) & 7, jz = std::min(j1, (jb << 3) + 7) & 7;
            // Rows ja..jz of the brick's 8x8 (j, k) bits: one byte per row.
            const std::uint64_t rows = (~std::uint64_t(0) >> (56 - 8 * (jz - ja))) << (8 * ja);
            for (int kb = k0 >> 3; kb <= k1 >> 3; ++kb) {
                const int ka = std::max(k0, kb << 3) & 7, kz = std::min(k1, (kb << 3) + 7) & 7;
                const std::uint64_t columns =
                    ((std::uint64_t(2) << kz) - (std::uint64_t(1) << ka)) * 0x0101010101010101ull;
                const std::uint64_t mask = rows & columns;
                for (int i = i0; i <= i1; ++i) {
                    const std::uint64_t* word = grid_.data() + grid_.wordIndex(i, jb << 3, kb << 3);
                    std::uint64_t bits = __atomic_load_n(word, __ATOMIC_RELAXED);
                    if (word == word_) bits |= mask_;
                    if ((bits & mask) != mask) return false;
                }
            }
        }
        return true;
    }

private:
    BitGrid& grid_;
    std::array<std::int32_t, 3> offset_;
    std::uint64_t* word_ = nullptr;
    std::uint64_t mask_ = 0;
};

}  // namespace hyvox::cpu
