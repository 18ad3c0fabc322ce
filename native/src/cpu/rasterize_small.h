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

// The bit of candidate t.lo + (du, dv, dw) (swizzled order) in acceptedSmallCandidates' answer.
constexpr int smallCandidateBit(int du, int dv, int dw) { return (du * kSmallSide + dv) * kSmallSide + dw; }

// The accepted candidates of a small triangle (fitsSmallPath), as smallCandidateBit bits.
std::uint64_t acceptedSmallCandidates(const TriangleSetup& t);

inline void rasterizeSmall(const TriangleSetup& t, WordMarker& marker) {
    std::uint64_t accepted = acceptedSmallCandidates(t);
    // Unswizzle: (u, v, w) is the cyclic triple starting after the dominant axis w.
    const int u_axis = t.w == 2 ? 0 : t.w + 1, v_axis = t.w == 0 ? 2 : t.w - 1;
    int lo[3], hi[3];
    lo[u_axis] = t.lo[0], lo[v_axis] = t.lo[1], lo[t.w] = t.lo[2];
    hi[u_axis] = t.hi[0], hi[v_axis] = t.hi[1], hi[t.w] = t.hi[2];
    auto voxelOf = [&](int bit, int p[3]) {
        p[u_axis] = t.lo[0] + bit / (kSmallSide * kSmallSide);
        p[v_axis] = t.lo[1] + bit / kSmallSide % kSmallSide;
        p[t.w] = t.lo[2] + bit % kSmallSide;
    };
    // Where the candidates stay within one brick along j and k (mostly), the accepted voxels
    // of each i share one word of the grid: one mark per word instead of one per voxel.
    if ((lo[1] >> 3) == (hi[1] >> 3) && (lo[2] >> 3) == (hi[2] >> 3)) {
        std::uint64_t rows[kSmallSide] = {};
        while (accepted) {
            int p[3];
            voxelOf(__builtin_ctzll(accepted), p);
            accepted &= accepted - 1;
            rows[p[0] - lo[0]] |= BitGrid::bitMask(p[1], p[2]);
        }
        for (int di = 0; di < kSmallSide; ++di)
            if (rows[di]) marker.markWord(lo[0] + di, lo[1], lo[2], rows[di]);
        return;
    }
    while (accepted) {
        int p[3];
        voxelOf(__builtin_ctzll(accepted), p);
        accepted &= accepted - 1;
        marker.mark(p[0], p[1], p[2]);
    }
}

}  // namespace hyvox::cpu
