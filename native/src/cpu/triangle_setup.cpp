// SPDX-License-Identifier: GPL-3.0-or-later
#include "cpu/triangle_setup.h"

#include <algorithm>
#include <cmath>

#include "core/avx2_clones.h"
#include "core/triangle_normal.h"

namespace hyvox::cpu {
namespace {

// Branch-free: normal signs are random per triangle, so branches would mispredict.
inline double signOf(double x) { return double(x > 0.0) - double(x < 0.0); }

// Edge tests of one projection (a, b) whose winding is sign(n_c), c the third axis of the
// cyclic triple (a, b, c). A zero winding means the triangle projects to a segment; the
// tests then pass trivially (the plane test already decides those voxels). The corners are
// given by reference (p[i] is corner i), so that no copy of them is read back.
template <bool Thin>
inline void setupProjection(const Corner3* const p[3], double winding, int a, int b, EdgeTest out[3]) {
    for (int i = 0; i < 3; ++i) {
        const Corner3& from = *p[i];
        const Corner3& to = *p[i == 2 ? 0 : i + 1];
        EdgeTest& e = out[i];
        e.na = -winding * (to[b] - from[b]);
        e.nb = winding * (to[a] - from[a]);
        e.va = from[a];
        e.vb = from[b];
        if constexpr (Thin) {
            // Voxel centre p + 1/2 against the diamond |da|+|db| <= 1/2 inscribed in the
            // voxel's projection: the support along (na, nb) is max(|na|, |nb|) / 2.
            e.offset = 0.5 * (e.na + e.nb) + 0.5 * std::max(std::fabs(e.na), std::fabs(e.nb));
        } else {
            // The voxel corner furthest along the inward normal ("critical point").
            e.offset = std::max(0.0, e.na) + std::max(0.0, e.nb);
        }
    }
}

// The setup once the dominant axis W is known: one instance per axis, so that the swizzle
// (u, v, w) = (W+1, W+2, W) mod 3 is fixed at compile time and every corner coordinate is
// read at a constant offset (a swizzle by a run-time index went through the stack, and the
// reloads stalled on the stores they overlapped).
template <bool Thin, int W>
__attribute__((always_inline)) inline SetupKind setupAlong(const Corner3* const c[3], const Corner3& n,
                                                           const CandidateRange& range, TriangleSetup& out) {
    constexpr int u = (W + 1) % 3, v = (W + 2) % 3, w = W;
    const std::array<int, 3>& lo = range.lo;
    const std::array<int, 3>& hi = range.hi;
    const std::array<bool, 3>& one = range.single;
    out.w = w;
    out.lo = {lo[u], lo[v], lo[w]};
    out.hi = {hi[u], hi[v], hi[w]};

    // Projections: (u,v) winds with n_w, (v,w) with n_u, (w,u) with n_v (cyclic triples).
    // Conservative only: a projection is redundant when the triangle's extent along one of
    // its two axes lies within one voxel's range. The projected triangle is connected, so
    // it then has a point inside every candidate voxel's square (its other coordinate
    // ranges over an interval meeting the square's), and the edge tests would all pass.
    // Those tests are set to pass trivially; small triangles skip most of the work.
    auto project = [&](double winding, int a, int b, EdgeTest* tests, bool redundant) {
        if (!Thin && redundant)
            for (int i = 0; i < 3; ++i) tests[i] = EdgeTest{0, 0, 0, 0, 0};
        else
            setupProjection<Thin>(c, winding, a, b, tests);
    };
    project(signOf(n[w]), u, v, out.uv, one[u] || one[v]);
    project(signOf(n[u]), v, w, out.vw, one[v] || one[w]);
    project(signOf(n[v]), w, u, out.wu, one[w] || one[u]);

    // The plane, with its normal flipped to point along +w so the depth range is ordered.
    const double flip = signOf(n[w]);
    out.normal = {flip * n[u], flip * n[v], flip * n[w]};
    out.origin = {(*c[0])[u], (*c[0])[v], (*c[0])[w]};
    if constexpr (Thin) {
        // Column centre: the plane's depth at (pu + 1/2, pv + 1/2).
        out.depth_lo_offset = out.depth_hi_offset = 0.5 * (out.normal[0] + out.normal[1]);
    } else {
        // The voxel box's extreme corners along the normal in (u, v).
        out.depth_lo_offset = std::max(0.0, out.normal[0]) + std::max(0.0, out.normal[1]);
        out.depth_hi_offset = std::min(0.0, out.normal[0]) + std::min(0.0, out.normal[1]);
    }
    return SetupKind::Full;
}

template <bool Thin>
__attribute__((always_inline)) inline SetupKind setup(const Corner3& c0, const Corner3& c1, const Corner3& c2,
                                                      const CandidateRange& range, TriangleSetup& out) {
    // Within one voxel's range along two axes, the triangle lies in one column of voxels;
    // its extent along the third axis is an interval meeting every candidate's range, so
    // each candidate's closed box holds a point of it. (Most triangles of a fine mesh.)
    if (!Thin && range.singleAxes() >= 2) {
        out.lo = range.lo;
        out.hi = range.hi;
        return SetupKind::AllCandidates;
    }

    // The corners in an order of their values alone, so every order of the same corners
    // rounds alike and sets the same voxels; the normal from the two shortest edges keeps a
    // sliver's width (core/triangle_normal.h). Neither rule depends on the winding:
    // conservative and thin voxels are the same for both sides.
    const Corner3* const given[3] = {&c0, &c1, &c2};
    const CornerOrder order = canonicalCornerOrder(c0, c1, c2);
    const Corner3* const c[3] = {given[order.index[0]], given[order.index[1]], given[order.index[2]]};
    const Corner3 n = canonicalNormal(*c[0], *c[1], *c[2]);
    const double an[3] = {std::fabs(n[0]), std::fabs(n[1]), std::fabs(n[2])};
    const int w = (an[0] >= an[1] && an[0] >= an[2]) ? 0 : (an[1] >= an[2] ? 1 : 2);
    if (an[w] == 0.0) {
        // No plane in voxel space (a needle whose near corners coincide there): what is left
        // is a segment or a point, which still touches voxels (rasterize_planeless.h).
        out.lo = range.lo;
        out.hi = range.hi;
        return SetupKind::Planeless;
    }
    switch (w) {
        case 0: return setupAlong<Thin, 0>(c, n, range, out);
        case 1: return setupAlong<Thin, 1>(c, n, range, out);
        default: return setupAlong<Thin, 2>(c, n, range, out);
    }
}

}  // namespace

CandidateRange candidateRange(const std::array<std::array<double, 3>, 3>& c, const std::array<std::int32_t, 3>& clip_lo,
                              const std::array<std::int32_t, 3>& clip_hi) {
    // Voxel i's closed box meets [lo, hi] iff lo - 1 <= i <= hi.
    CandidateRange r;
    for (int a = 0; a < 3; ++a) {
        const double mn = std::min(std::min(c[0][a], c[1][a]), c[2][a]);
        const double mx = std::max(std::max(c[0][a], c[1][a]), c[2][a]);
        const int first = ceilToInt(clampCoord(mn)) - 1, last = floorToInt(clampCoord(mx));
        r.lo[a] = std::max(clip_lo[a], first);
        r.hi[a] = std::min(clip_hi[a], last);
        r.single[a] = first == last;
    }
    return r;
}

void setupEdgeTests(const std::array<std::array<double, 3>, 3>& c, double winding, int a, int b, Mode mode,
                    EdgeTest out[3]) {
    const Corner3* const p[3] = {&c[0], &c[1], &c[2]};
    if (mode == Mode::Thin)
        setupProjection<true>(p, winding, a, b, out);
    else
        setupProjection<false>(p, winding, a, b, out);
}

HYVOX_AVX2_CLONES
SetupKind setupTriangle(const Corner3& c0, const Corner3& c1, const Corner3& c2, Mode mode, const CandidateRange& range,
                        TriangleSetup& out) {
    return mode == Mode::Thin ? setup<true>(c0, c1, c2, range, out) : setup<false>(c0, c1, c2, range, out);
}

// After the clones: a function built as clones is defined before its first use (clang).
SetupKind setupTriangle(const std::array<std::array<double, 3>, 3>& corners, Mode mode,
                        const std::array<std::int32_t, 3>& clip_lo, const std::array<std::int32_t, 3>& clip_hi,
                        TriangleSetup& out) {
    const CandidateRange range = candidateRange(corners, clip_lo, clip_hi);
    if (range.outside()) return SetupKind::Outside;
    return setupTriangle(corners[0], corners[1], corners[2], mode, range, out);
}

}  // namespace hyvox::cpu
