// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The same factored test as rasterize_triangle.h, for triangles whose candidate range is at
// most 4 voxels along every axis (most triangles of a finely tessellated mesh). The general
// loops spend their time on unpredictable branches (row, column and depth loops of one to
// three steps, early-outs); here the candidates are decided without branches into a bit
// mask, four columns of the dominant plane at a time in vector lanes (rasterize_small.cpp),
// with the very same arithmetic per voxel as the general loops (so both paths decide every
// voxel alike), and only the accepted voxels are marked.
#include <cstdint>

#include "cpu/mark_voxels.h"
#include "cpu/triangle_setup.h"

namespace hyvox::cpu {

// At most this many candidates along each axis.
constexpr int kSmallSide = 4;

inline bool fitsSmallPath(const TriangleSetup& t) {
    return t.hi[0] - t.lo[0] < kSmallSide && t.hi[1] - t.lo[1] < kSmallSide && t.hi[2] - t.lo[2] < kSmallSide;
}

// The bit of offset (a, b, c) in a box of kSmallSide voxels a side.
constexpr int smallBoxBit(int a, int b, int c) { return (a * kSmallSide + b) * kSmallSide + c; }

// The accepted candidates of a small triangle (fitsSmallPath): bit smallBoxBit(x, y, z) for
// voxel lo + (x, y, z), lo its lowest candidate in grid order (t.lo unswizzled).
std::uint64_t acceptedSmallCandidates(const TriangleSetup& t);

inline void rasterizeSmall(const TriangleSetup& t, WordMarker& marker) {
    std::uint64_t accepted = acceptedSmallCandidates(t);
    // Unswizzle: (u, v, w) is the cyclic triple starting after the dominant axis w.
    const int u_axis = t.w == 2 ? 0 : t.w + 1, v_axis = t.w == 0 ? 2 : t.w - 1;
    int lo[3], hi[3];
    lo[u_axis] = t.lo[0], lo[v_axis] = t.lo[1], lo[t.w] = t.lo[2];
    hi[u_axis] = t.hi[0], hi[v_axis] = t.hi[1], hi[t.w] = t.hi[2];
    // Where the candidates stay within one brick along j and k (mostly), the accepted voxels
    // of each i share one word of the grid (bit (j & 7) * 8 + (k & 7)): the box's 4 x 4 (y, z)
    // bits of row x are spread out to it, one mark per word.
    if ((lo[1] >> 3) == (hi[1] >> 3) && (lo[2] >> 3) == (hi[2] >> 3)) {
        const int first_bit = (lo[1] & 7) * 8 + (lo[2] & 7);
        for (int x = 0; x <= hi[0] - lo[0]; ++x) {
            const std::uint64_t row = accepted >> smallBoxBit(x, 0, 0);
            std::uint64_t word = 0;
            for (int y = 0; y < kSmallSide; ++y)
                word |= (row >> smallBoxBit(0, y, 0) & ((1u << kSmallSide) - 1)) << (8 * y);
            if (word) marker.markWord(lo[0] + x, lo[1], lo[2], word << first_bit);
        }
        return;
    }
    while (accepted) {
        const int bit = __builtin_ctzll(accepted);
        accepted &= accepted - 1;
        marker.mark(lo[0] + bit / (kSmallSide * kSmallSide), lo[1] + bit / kSmallSide % kSmallSide,
                    lo[2] + bit % kSmallSide);
    }
}

}  // namespace hyvox::cpu
