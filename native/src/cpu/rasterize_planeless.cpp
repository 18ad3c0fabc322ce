// SPDX-License-Identifier: GPL-3.0-or-later
#include "cpu/rasterize_planeless.h"

#include <algorithm>

#include "core/clamp_coord.h"
#include "core/triangle_normal.h"
#include "cpu/triangle_setup.h"

namespace hyvox::cpu {
namespace {

// The three coordinate planes (a, b) and, per plane, each edge's test with both windings.
constexpr int kPlanes[3][2] = {{0, 1}, {1, 2}, {2, 0}};

struct SlabTests {
    EdgeTest edges[3][6];
    bool accepts(int i, int j, int k) const {
        const double p[3] = {double(i), double(j), double(k)};
        for (int plane = 0; plane < 3; ++plane) {
            const double pa = p[kPlanes[plane][0]], pb = p[kPlanes[plane][1]];
            for (const EdgeTest& e : edges[plane])
                if (!passes(e, pa, pb)) return false;
        }
        return true;
    }
};

}  // namespace

void rasterizePlaneless(const std::array<std::array<double, 3>, 3>& given, Mode mode, const std::array<int, 3>& lo,
                        const std::array<int, 3>& hi, WordMarker& marker) {
    // The corners in the order setupTriangle takes them (core/triangle_normal.h): every
    // order of the same corners rounds alike.
    const CornerOrder order = canonicalCornerOrder(given[0], given[1], given[2]);
    const std::array<std::array<double, 3>, 3> c{given[order.index[0]], given[order.index[1]], given[order.index[2]]};
    SlabTests tests;
    for (int plane = 0; plane < 3; ++plane) {
        setupEdgeTests(c, 1.0, kPlanes[plane][0], kPlanes[plane][1], mode, tests.edges[plane]);
        setupEdgeTests(c, -1.0, kPlanes[plane][0], kPlanes[plane][1], mode, tests.edges[plane] + 3);
    }

    // The longest axis m, and the corners at either end of it (the segment's ends: the third
    // corner lies between them, on the segment up to rounding).
    int m = 0;
    double longest = -1.0;
    for (int a = 0; a < 3; ++a) {
        const double extent = std::max({c[0][a], c[1][a], c[2][a]}) - std::min({c[0][a], c[1][a], c[2][a]});
        if (extent > longest) longest = extent, m = a;
    }
    int first = 0, last = 0;
    for (int i = 1; i < 3; ++i) {
        if (c[i][m] < c[first][m]) first = i;
        if (c[i][m] > c[last][m]) last = i;
    }
    const auto& from = c[first];
    const auto& to = c[last];

    // Slab x_m in [s, s + 1] (the closed boxes of voxels s along m) holds the part of the
    // segment between parameters t0 and t1; along the other axes that part spans at most one
    // voxel (m is the longest axis), so its candidates are the voxels whose closed boxes meet
    // its range, widened by one voxel on each side against rounding (the tests decide).
    for (int s = lo[m]; s <= hi[m]; ++s) {
        double t0 = 0.0, t1 = 1.0;
        if (longest > 0.0) {
            t0 = std::clamp((s - from[m]) / longest, 0.0, 1.0);
            t1 = std::clamp((s + 1 - from[m]) / longest, 0.0, 1.0);
        }
        std::array<int, 3> slab_lo = lo, slab_hi = hi;
        slab_lo[m] = slab_hi[m] = s;
        for (int a = 0; a < 3; ++a) {
            if (a == m) continue;
            const double x0 = from[a] + t0 * (to[a] - from[a]), x1 = from[a] + t1 * (to[a] - from[a]);
            slab_lo[a] = std::max(lo[a], ceilToInt(clampCoord(std::min(x0, x1))) - 2);
            slab_hi[a] = std::min(hi[a], floorToInt(clampCoord(std::max(x0, x1))) + 1);
        }
        for (int i = slab_lo[0]; i <= slab_hi[0]; ++i)
            for (int j = slab_lo[1]; j <= slab_hi[1]; ++j)
                for (int k = slab_lo[2]; k <= slab_hi[2]; ++k)
                    if (tests.accepts(i, j, k)) marker.mark(i, j, k);
    }
}

}  // namespace hyvox::cpu
