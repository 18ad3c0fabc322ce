// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Set bits of a word, branch-free. The build targets baseline x86-64, where
// __builtin_popcountll is a library call; the inside values rank voxels in their inner loops.
#include <cstdint>

namespace hyvox::attributes {

inline int popcount(std::uint64_t word) {
    word = word - ((word >> 1) & 0x5555555555555555ull);
    word = (word & 0x3333333333333333ull) + ((word >> 2) & 0x3333333333333333ull);
    word = (word + (word >> 4)) & 0x0f0f0f0f0f0f0f0full;
    return int((word * 0x0101010101010101ull) >> 56);
}

// The set bits of `word` below bit `bit & 63`.
inline int popcountBelow(std::uint64_t word, int bit) {
    return popcount(word & ((std::uint64_t(1) << (bit & 63)) - 1));
}

}  // namespace hyvox::attributes
