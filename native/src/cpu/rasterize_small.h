// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The same factored test as rasterize_triangle.h, for triangles whose candidate range is at
// most 3 voxels along every axis (most triangles of a finely tessellated mesh). The general
// loops spend their time on unpredictable branches (row, column and depth loops of one to
// three steps, early-outs); here the candidates are decided without branches into a bit
// mask, four columns of the dominant plane at a time in vector lanes (rasterize_small.cpp),
// with the very same arithmetic per voxel as the general loops (so both paths decide every
// voxel alike), and only the accepted voxels are marked.
#include <cstdint>

#include "cpu/mark_voxels.h"
#include "cpu/triangle_setup.h"

namespace hyvox::cpu {

inline bool fitsSmallPath(const TriangleSetup& t) {
    return t.hi[0] - t.lo[0] <= 2 && t.hi[1] - t.lo[1] <= 2 && t.hi[2] - t.lo[2] <= 2;
}

// Bit (du * 3 + dv) * 3 + dw is set for each accepted candidate t.lo + (du, dv, dw) (swizzled
// order, t.hi - t.lo <= 2 along every axis).
std::uint32_t acceptedSmallCandidates(const TriangleSetup& t);

inline void rasterizeSmall(const TriangleSetup& t, WordMarker& marker) {
    std::uint32_t accepted = acceptedSmallCandidates(t);
    // Unswizzle: (u, v, w) is the cyclic triple starting after the dominant axis w.
    const int u_axis = t.w == 2 ? 0 : t.w + 1, v_axis = t.w == 0 ? 2 : t.w - 1;
    int lo[3], hi[3];
    lo[u_axis] = t.lo[0], lo[v_axis] = t.lo[1], lo[t.w] = t.lo[2];
    hi[u_axis] = t.hi[0], hi[v_axis] = t.hi[1], hi[t.w] = t.hi[2];
    auto voxelOf = [&](int bit, int p[3]) {
        p[u_axis] = t.lo[0] + bit / 9;
        p[v_axis] = t.lo[1] + bit / 3 % 3;
        p[t.w] = t.lo[2] + bit % 3;
    };
    // Where the candidates stay within one brick along j and k (mostly), the accepted voxels
    // of each i share one word of the grid: one mark per word instead of one per voxel.
    if ((lo[1] >> 3) == (hi[1] >> 3) && (lo[2] >> 3) == (hi[2] >> 3)) {
        std::uint64_t rows[3] = {0, 0, 0};
        while (accepted) {
            int p[3];
            voxelOf(__builtin_ctz(accepted), p);
            accepted &= accepted - 1;
            rows[p[0] - lo[0]] |= BitGrid::bitMask(p[1], p[2]);
        }
        for (int di = 0; di < 3; ++di)
            if (rows[di]) marker.markWord(lo[0] + di, lo[1], lo[2], rows[di]);
        return;
    }
    while (accepted) {
        int p[3];
        voxelOf(__builtin_ctz(accepted), p);
        accepted &= accepted - 1;
        marker.mark(p[0], p[1], p[2]);
    }
}

}  // namespace hyvox::cpu
