// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The same factored test as rasterize_triangle.h, for triangles whose candidate range is at
// most 3 voxels along every axis (most triangles of a finely tessellated mesh). The general
// loops spend their time on unpredictable branches (row, column and depth loops of one to
// three steps, early-outs); here the candidates are decided in loops of fixed length
// without branches into a bit mask, with the very same arithmetic as the general loops (so
// both paths decide every voxel alike), and only the accepted voxels are marked.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>

#include "cpu/mark_voxels.h"
#include "cpu/triangle_setup.h"

namespace hyvox::cpu {

inline bool fitsSmallPath(const TriangleSetup& t) {
    return t.hi[0] - t.lo[0] <= 2 && t.hi[1] - t.lo[1] <= 2 && t.hi[2] - t.lo[2] <= 2;
}

// The NU x NV x NW candidates from t.lo (each 1 to 3: t.hi - t.lo + 1).
template <int NU, int NV, int NW>
inline void rasterizeFixed(const TriangleSetup& t, WordMarker& marker) {
    const double nu = t.normal[0], nv = t.normal[1], inv_nw = 1.0 / t.normal[2];
    const double ou = t.origin[0], ov = t.origin[1], ow = t.origin[2];
    std::uint32_t accepted = 0;  // bit (du * NV + dv) * NW + dw for voxel lo + (du, dv, dw)
    for (int dv = 0; dv < NV; ++dv) {
        const double pvd = t.lo[1] + dv;
        double uv_row[3], vw_row[3];
        for (int i = 0; i < 3; ++i) {
            uv_row[i] = t.uv[i].nb * (pvd - t.uv[i].vb) + t.uv[i].offset;
            vw_row[i] = t.vw[i].na * (pvd - t.vw[i].va) + t.vw[i].offset;
        }
        const double plane_v = nv * (pvd - ov);
        for (int du = 0; du < NU; ++du) {
            const int pu = t.lo[0] + du;
            const double pud = pu;
            bool column = (pu <= t.hi[0]) & (t.lo[1] + dv <= t.hi[1]);
            for (int i = 0; i < 3; ++i) column &= t.uv[i].na * (pud - t.uv[i].va) + uv_row[i] >= 0.0;
            const double d = nu * (pud - ou) + plane_v;
            const int w0 = ceilToInt(clampCoord(ow - (d + t.depth_lo_offset) * inv_nw)) - 1;
            const int w1 = std::min(t.hi[2], floorToInt(clampCoord(ow - (d + t.depth_hi_offset) * inv_nw)));
            double wu_col[3];
            for (int i = 0; i < 3; ++i) wu_col[i] = t.wu[i].nb * (pud - t.wu[i].vb) + t.wu[i].offset;
            for (int dw = 0; dw < NW; ++dw) {
                const int pw = t.lo[2] + dw;
                const double pwd = pw;
                bool inside = column & (pw >= w0) & (pw <= w1);
                for (int i = 0; i < 3; ++i) {
                    inside &= t.vw[i].nb * (pwd - t.vw[i].vb) + vw_row[i] >= 0.0;
                    inside &= t.wu[i].na * (pwd - t.wu[i].va) + wu_col[i] >= 0.0;
                }
                accepted |= std::uint32_t(inside) << ((du * NV + dv) * NW + dw);
            }
        }
    }
    // Unswizzle: (u, v, w) is the cyclic triple starting after the dominant axis w.
    const int u_axis = t.w == 2 ? 0 : t.w + 1, v_axis = t.w == 0 ? 2 : t.w - 1;
    while (accepted) {
        const int bit = __builtin_ctz(accepted);
        accepted &= accepted - 1;
        int p[3];
        p[u_axis] = t.lo[0] + bit / (NV * NW);
        p[v_axis] = t.lo[1] + (bit / NW) % NV;
        p[t.w] = t.lo[2] + bit % NW;
        marker.mark(p[0], p[1], p[2]);
    }
}

// One instance per candidate count along each axis (1 to 3): a triangle that lies within
// one voxel's range along one axis tests half the voxels a 2 x 2 x 2 loop would.
using SmallRasterizer = void (*)(const TriangleSetup&, WordMarker&);
template <std::size_t... Code>
constexpr std::array<SmallRasterizer, sizeof...(Code)> smallRasterizers(std::index_sequence<Code...>) {
    return {&rasterizeFixed<int(Code / 9) + 1, int(Code / 3 % 3) + 1, int(Code % 3) + 1>...};
}

inline void rasterizeSmall(const TriangleSetup& t, WordMarker& marker) {
    static constexpr std::array<SmallRasterizer, 27> kBySize = smallRasterizers(std::make_index_sequence<27>{});
    kBySize[std::size_t((t.hi[0] - t.lo[0]) * 9 + (t.hi[1] - t.lo[1]) * 3 + (t.hi[2] - t.lo[2]))](t, marker);
}

}  // namespace hyvox::cpu
