// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The inner loops of the factored test: rows of the dominant (u, v) plane, the columns of
// a row that pass the 2D test, the depth range along w, and the two remaining projections.
// Conservative and thin differ only in the offsets prepared by setupTriangle.
#include <algorithm>

#include "cpu/mark_voxels.h"
#include "cpu/triangle_setup.h"

namespace hyvox::cpu {

// Marks the accepted voxels of rows [row_begin, row_end) of the dominant plane. W is the
// dominant axis: the swizzled voxel (pu, pv, pw) is stored at unswizzled coordinates
// ((u, v, w) is the cyclic triple starting after W).
template <int W>
inline void rasterizeRows(const TriangleSetup& t, int row_begin, int row_end, WordMarker& marker) {
    const double nu = t.normal[0], nv = t.normal[1], inv_nw = 1.0 / t.normal[2];
    const double ou = t.origin[0], ov = t.origin[1], ow = t.origin[2];
    const bool wide = t.hi[0] - t.lo[0] > 6;

    for (int pv = row_begin; pv < row_end; ++pv) {
        const double pvd = pv;
        // Per-row parts of the dominant-plane and (v, w) edge tests.
        double uv_row[3], vw_row[3];
        for (int i = 0; i < 3; ++i) {
            uv_row[i] = t.uv[i].nb * (pvd - t.uv[i].vb) + t.uv[i].offset;
            vw_row[i] = t.vw[i].na * (pvd - t.vw[i].va) + t.vw[i].offset;
        }
        int pu0 = t.lo[0], pu1 = t.hi[0];
        if (wide) {
            // Narrow the columns to where the dominant-plane edge tests can pass (solved per
            // edge, widened by one column against rounding; every column is still tested
            // below, so this changes speed only).
            double from = pu0, to = pu1;
            bool empty = false;
            for (int i = 0; i < 3; ++i) {
                const EdgeTest& e = t.uv[i];
                if (e.na > 0.0)
                    from = std::max(from, e.va - uv_row[i] / e.na);
                else if (e.na < 0.0)
                    to = std::min(to, e.va - uv_row[i] / e.na);
                else
                    empty |= uv_row[i] < 0.0;
            }
            if (empty || from > to + 2.0) continue;
            pu0 = std::max(pu0, floorToInt(clampCoord(from)) - 1);
            pu1 = std::min(pu1, ceilToInt(clampCoord(to)) + 1);
        }
        const double plane_v = nv * (pvd - ov);

        for (int pu = pu0; pu <= pu1; ++pu) {
            const double pud = pu;
            if (t.uv[0].na * (pud - t.uv[0].va) + uv_row[0] < 0.0 ||
                t.uv[1].na * (pud - t.uv[1].va) + uv_row[1] < 0.0 || t.uv[2].na * (pud - t.uv[2].va) + uv_row[2] < 0.0)
                continue;
            // Depth range: the voxels of this column that the plane meets (thin: the one or,
            // on a voxel plane, two voxels holding the plane's depth at the column centre).
            const double d = nu * (pud - ou) + plane_v;
            const int w0 = std::max(t.lo[2], ceilToInt(clampCoord(ow - (d + t.depth_lo_offset) * inv_nw)) - 1);
            const int w1 = std::min(t.hi[2], floorToInt(clampCoord(ow - (d + t.depth_hi_offset) * inv_nw)));
            if (w0 > w1) continue;
            double wu_col[3];
            for (int i = 0; i < 3; ++i) wu_col[i] = t.wu[i].nb * (pud - t.wu[i].vb) + t.wu[i].offset;
            for (int pw = w0; pw <= w1; ++pw) {
                const double pwd = pw;
                bool inside = true;
                for (int i = 0; i < 3; ++i) {
                    inside &= t.vw[i].nb * (pwd - t.vw[i].vb) + vw_row[i] >= 0.0;
                    inside &= t.wu[i].na * (pwd - t.wu[i].va) + wu_col[i] >= 0.0;
                }
                if (!inside) continue;
                if constexpr (W == 2)
                    marker.mark(pu, pv, pw);
                else if constexpr (W == 0)
                    marker.mark(pw, pu, pv);
                else
                    marker.mark(pv, pw, pu);
            }
        }
    }
}

}  // namespace hyvox::cpu
