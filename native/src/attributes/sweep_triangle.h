// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// All pieces of one triangle in a box of voxels: the slab sweep (sweep_cells.h) along the two
// axes after the triangle's dominant one, then up the dominant axis, so a column holds at most
// a few voxels; columns that lie wholly inside the triangle are measured without cutting
// (inner_columns.h), the rest by the sweep.
#include <array>
#include <cmath>
#include <cstdint>

#include "attributes/clip_to_voxel.h"
#include "attributes/inner_columns.h"
#include "attributes/sweep_cells.h"

namespace hyvox::attributes {

using Voxel = std::array<int, 3>;

// The voxels a caller wants pieces in, asked along the sweep's axes (a, b, h) = (axis d + 1,
// d + 2, d) mod 3: any in slab a, any in column (a, b), and one voxel.
struct EveryVoxel {
    bool slab(int /*d*/, int /*a*/) const { return true; }
    bool column(int /*d*/, int /*a*/, int /*b*/) const { return true; }
    bool voxel(const Voxel& /*v*/) const { return true; }
};

namespace detail {

template <int D, typename Wanted, typename Visit>
std::uint64_t sweepAlong(const std::array<Point, 3>& corners, const TriangleFrame& frame, const Voxel& lo,
                         const Voxel& hi, const Wanted& wanted, Visit& visit) {
    constexpr int A = (D + 1) % 3, B = (D + 2) % 3;
    std::array<Point, 3> p;
    for (std::size_t m = 0; m < 3; ++m) p[m] = {corners[m][A], corners[m][B], corners[m][D]};
    const int lo_a = lo[A], hi_a = hi[A], lo_b = lo[B], hi_b = hi[B], lo_h = lo[D], hi_h = hi[D];
    const auto voxelOf = [](int a, int b, int h) {
        Voxel v;
        v[A] = a, v[B] = b, v[D] = h;
        return v;
    };
    const auto unpermuted = [](const Point& q) {
        Point r;
        r[A] = q[0], r[B] = q[1], r[D] = q[2];
        return r;
    };
    const double scale = frame.projectedAreaScale();
    // The plane over (a, b), when the triangle is not flat along its dominant axis.
    const Point e1{p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]};
    const Point e2{p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
    const Point n{e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    // A triangle holds a unit square in projection only if its projection's area is at least
    // 2 (|n[2]| / 2): smaller ones skip the search.
    const bool has_inner = std::fabs(n[2]) >= 4.0 && scale != 0;
    const LiftedPlane plane{p[0], has_inner ? -n[0] / n[2] : 0.0, has_inner ? -n[1] / n[2] : 0.0,
                            2.0 * std::fabs(scale)};
    std::uint64_t inner_pieces = 0;
    const InnerColumns inner_columns(p, has_inner ? n : Point{0, 0, 1});

    SweepLines lines;
    const TracedPolygon whole = tracedTriangle(p, lines);
    ClippedPiece piece;
    sweepSlabs<0>(whole, lo_a, hi_a, lines, true, [&](int a, const TracedPolygon& slab) {
        if (!wanted.slab(D, a)) return;
        int inner_lo = 1, inner_hi = 0;
        if (has_inner) {
            inner_columns.ofSlab(a, inner_lo, inner_hi);
            inner_lo = std::max(inner_lo, lo_b);
            inner_hi = std::min(inner_hi, hi_b);
        }
        for (int b = inner_lo; b <= inner_hi; ++b) {
            if (!wanted.column(D, a, b)) continue;
            innerColumnPieces(plane, a, b, lo_h, hi_h, [&](int h, ClippedPiece& inner) {
                const Voxel v = voxelOf(a, b, h);
                if (!wanted.voxel(v)) return;
                ++inner_pieces;
                inner.centroid = unpermuted(inner.centroid);
                visit(v, inner);
            });
        }
        sweepSlabs<1>(
            slab, lo_b, hi_b, lines, true,
            [&](int b, const TracedPolygon& column) {
                if (!wanted.column(D, a, b)) return;
                sweepSlabs<2>(column, lo_h, hi_h, lines, false, [&](int h, const TracedPolygon& cell) {
                    const Voxel v = voxelOf(a, b, h);
                    if (!wanted.voxel(v)) return;
                    measurePiece(cell.shape, 0, 1, scale, piece);
                    piece.centroid = unpermuted(piece.centroid);
                    visit(v, piece);
                });
            },
            inner_lo, inner_hi);
    });
    return inner_pieces;
}

}  // namespace detail

// Calls visit(voxel, piece) for every voxel of [lo, hi] (inclusive, per axis) that `wanted`
// holds and the triangle's closed box meets, `piece` valid during the call. Returns how many
// of them came from inner columns.
template <typename Wanted, typename Visit>
std::uint64_t sweepTriangle(const std::array<Point, 3>& corners, const TriangleFrame& frame, const Voxel& lo,
                            const Voxel& hi, const Wanted& wanted, Visit&& visit) {
    // The dominant axis is the one after the frame's two projection axes.
    const int d = 3 - frame.projectionAxes()[0] - frame.projectionAxes()[1];
    switch (d) {
        case 0: return detail::sweepAlong<0>(corners, frame, lo, hi, wanted, visit);
        case 1: return detail::sweepAlong<1>(corners, frame, lo, hi, wanted, visit);
        default: return detail::sweepAlong<2>(corners, frame, lo, hi, wanted, visit);
    }
}

}  // namespace hyvox::attributes
