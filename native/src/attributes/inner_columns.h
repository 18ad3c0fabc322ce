// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The pieces of a triangle in a column of voxels that lies wholly inside it (seen along the
// triangle's dominant axis): no edge of the triangle enters the column, so the triangle there
// is the unit square lifted onto its plane, and the voxels cut it into bands between
// consecutive planes h = k of the dominant axis. Each band is found from the square's four
// heights alone (no polygon is cut), in the column's own coordinates (0..1), and measured in
// 2D; most pieces of a large triangle are of this kind (docs/design.md, "Attributes").
//
// Coordinates here are permuted so that the dominant axis is the last: (a, b, h).
#include <algorithm>
#include <cmath>

#include "attributes/clip_to_voxel.h"

namespace hyvox::attributes {

// A triangle's plane over the (a, b) lattice, with its dominant axis last (|n[2]| largest).
struct LiftedPlane {
    Point origin;             // a corner of the triangle
    double slope_a, slope_b;  // dh/da, dh/db (each within [-1, 1])
    double area_scale;        // area on the plane per area in (a, b)

    // The height over lattice point (a, b): the same expression wherever it is asked, so
    // columns that share a lattice edge cut it at the same points.
    double height(double a, double b) const {
        return origin[2] + slope_a * (a - origin[0]) + slope_b * (b - origin[1]);
    }
};

// The columns of a triangle that lie inside its projection on (a, b), at least a hair (1e-7
// voxel) from every edge, so that rounding cannot put an edge inside one. Set up once per
// triangle (its permuted corners `p`, normal `n` = (p1 - p0) x (p2 - p0), n[2] != 0).
class InnerColumns {
public:
    InnerColumns(const std::array<Point, 3>& p, const Point& n) {
        const double side = n[2] > 0 ? 1.0 : -1.0;  // the inside is on the left of each edge
        for (std::size_t m = 0; m < 3; ++m) {
            Edge& e = edges_[m];
            const Point& q = p[m];
            const Point& r = p[(m + 1) % 3];
            e.q_a = q[0], e.q_b = q[1];
            e.along_a = side * (r[0] - q[0]), e.along_b = side * (r[1] - q[1]);
            e.inverse_a = e.along_a != 0 ? 1.0 / e.along_a : 0.0;
            e.margin = 1e-7 * (std::fabs(e.along_a) + std::fabs(e.along_b));
        }
    }

    // The columns [lo, hi] along b of slab a..a + 1 (lo > hi: none).
    void ofSlab(int a, int& lo, int& hi) const {
        double from = -1e300, to = 1e300;  // the b range the squares' corners may take
        for (const Edge& e : edges_) {
            // Inside: along_a * (b - q_b) - along_b * (a - q_a) >= margin at the four corners.
            const double need =
                e.margin + std::max(e.along_b * (double(a) - e.q_a), e.along_b * (double(a) + 1.0 - e.q_a));
            if (e.along_a > 0) {
                from = std::max(from, e.q_b + need * e.inverse_a);
            } else if (e.along_a < 0) {
                to = std::min(to, e.q_b + need * e.inverse_a);
            } else if (need > 0) {
                lo = 1, hi = 0;
                return;
            }
        }
        if (!(from <= to - 1.0)) {
            lo = 1, hi = 0;
            return;
        }
        // Squares [b, b + 1] with from <= b and b + 1 <= to (clamped first: no int overflow).
        lo = int(std::ceil(std::clamp(from, -1e9, 1e9)));
        hi = int(std::floor(std::clamp(to, -1e9, 1e9))) - 1;
    }

private:
    struct Edge {
        double q_a, q_b, along_a, along_b, inverse_a, margin;
    };
    std::array<Edge, 3> edges_;
};

namespace detail {

// The unit square's corners counter-clockwise in (a, b), in the column's coordinates, and
// each edge's end first in lexicographic order of (a, b): neighbouring columns cross their
// shared edge from the same end, so they cut it at the same point.
constexpr double kSquareA[4] = {0, 1, 1, 0}, kSquareB[4] = {0, 0, 1, 1};
constexpr int kEdgeLow[4] = {0, 1, 3, 0}, kEdgeHigh[4] = {1, 2, 2, 3};

// A polygon in the column's coordinates (corners a, b and the height h of each) and its
// shoelace sums: twice its area and 3 * twice its area times its centroid.
struct ColumnPolygon {
    double a[8], b[8], h[8];
    int n = 0;
    double twice_area = 0, moment_a = 0, moment_b = 0;

    void add(double pa, double pb, double ph) {
        if (n == 8) return;  // a convex cut of the square has at most 6 corners
        a[n] = pa, b[n] = pb, h[n++] = ph;
    }
    void measure() {
        for (int c = 0; c < n; ++c) {
            const int next = c + 1 < n ? c + 1 : 0;
            const double cross = a[c] * b[next] - a[next] * b[c];
            twice_area += cross;
            moment_a += (a[c] + a[next]) * cross;
            moment_b += (b[c] + b[next]) * cross;
        }
    }
};

// The part of `in` with h <= level (`below`) or h >= level (a crossing interpolated between
// the polygon's corners: for the rare columns squarePart does not serve).
inline void clipAtLevel(const ColumnPolygon& in, double level, bool below, ColumnPolygon& out) {
    for (int c = 0; c < in.n; ++c) {
        const int next = c + 1 < in.n ? c + 1 : 0;
        const double hc = in.h[c], hn = in.h[next];
        if (below ? hc <= level : hc >= level) out.add(in.a[c], in.b[c], hc);
        if ((hc < level && hn > level) || (hc > level && hn < level)) {
            const double t = (level - hc) / (hn - hc);
            out.add(in.a[c] + (in.a[next] - in.a[c]) * t, in.b[c] + (in.b[next] - in.b[c]) * t, level);
        }
    }
}

// The part of the square with h <= level (`below`) or h >= level, its corners in order.
inline void squarePart(const double (&f)[4], double level, bool below, ColumnPolygon& out) {
    for (int c = 0; c < 4; ++c) {
        const int next = (c + 1) & 3;
        const double fc = f[c], fn = f[next];
        if (below ? fc <= level : fc >= level) out.add(kSquareA[c], kSquareB[c], fc);
        if ((fc < level && fn > level) || (fc > level && fn < level)) {
            const int low = kEdgeLow[c], high = kEdgeHigh[c];
            const double t = (level - f[low]) / (f[high] - f[low]);
            out.add(kSquareA[low] + (kSquareA[high] - kSquareA[low]) * t,
                    kSquareB[low] + (kSquareB[high] - kSquareB[low]) * t, level);
        }
    }
    out.measure();
}

}  // namespace detail

// Calls visit(k, piece) for every k in [lo, hi] whose closed box [k, k + 1] along h meets the
// lifted square of column (a, b) (an inner column of the triangle `plane` lies in), the piece
// in permuted coordinates. The plane's slopes are at most 1, so the square spans at most 2 in
// h: at most 3 pieces with area, plus touches where a corner lies on a plane h = k. A piece
// is the whole square, a part of it cut off by one plane (the smaller side, measured
// directly), or the square less such parts (then at least a quarter of it: its centroid
// comes out of the differences well conditioned).
template <typename Visit>
void innerColumnPieces(const LiftedPlane& plane, int a, int b, int lo, int hi, Visit&& visit) {
    using detail::ColumnPolygon;
    double f[4];
    for (int c = 0; c < 4; ++c) f[c] = plane.height(double(a) + detail::kSquareA[c], double(b) + detail::kSquareB[c]);
    const double f_min = std::min({f[0], f[1], f[2], f[3]}), f_max = std::max({f[0], f[1], f[2], f[3]});
    // Clamped before the conversions: a far plane cannot overflow an int.
    const double low_clamp = double(lo) - 4, high_clamp = double(hi) + 4;
    const double floor_min = std::floor(std::clamp(f_min, low_clamp, high_clamp));
    const double ceil_max = std::ceil(std::clamp(f_max, low_clamp, high_clamp));
    ClippedPiece piece;
    const auto fromSums = [&](double twice_area, double moment_a, double moment_b) {
        piece.area = 0.5 * twice_area * plane.area_scale;
        const double inverse = 1.0 / (3.0 * twice_area);
        piece.centroid[0] = double(a) + moment_a * inverse;
        piece.centroid[1] = double(b) + moment_b * inverse;
        piece.centroid[2] = plane.height(piece.centroid[0], piece.centroid[1]);
    };
    const auto fromPolygon = [&](const ColumnPolygon& part) {
        if (0.5 * part.twice_area * plane.area_scale >= kTouchArea) {
            fromSums(part.twice_area, part.moment_a, part.moment_b);
            return;
        }
        Polygon touch;  // a touch, or a sliver rounding left without area: as the sweep measures it
        touch.n = part.n;
        for (int c = 0; c < part.n; ++c)
            touch.p[std::size_t(c)] = {double(a) + part.a[c], double(b) + part.b[c], part.h[c]};
        measurePiece(touch, 0, 1, 0.5 * plane.area_scale, piece);
    };
    const auto touchAt = [&](double level) {  // the corners on plane h = level (f_min or f_max)
        ColumnPolygon corners;
        for (int c = 0; c < 4; ++c)
            if (f[c] == level) corners.add(detail::kSquareA[c], detail::kSquareB[c], f[c]);
        corners.measure();
        fromPolygon(corners);
    };
    if (f_min == f_max) {  // flat: the whole square, in both voxels when it lies on their face
        for (int k = std::max(lo, int(ceil_max) - 1); k <= std::min(hi, int(floor_min)); ++k) {
            fromSums(2.0, 3.0, 3.0);
            visit(k, piece);
        }
        return;
    }
    const int first_band = int(floor_min), last_band = int(ceil_max) - 1;  // the voxels with area
    if (double(first_band) == f_min && first_band - 1 >= lo && first_band - 1 <= hi) {
        touchAt(f_min);
        visit(first_band - 1, piece);
    }
    const int bands = last_band - first_band + 1;
    if (bands == 1) {
        if (first_band >= lo && first_band <= hi) {
            fromSums(2.0, 3.0, 3.0);
            visit(first_band, piece);
        }
    } else if (bands == 2) {
        // One plane cuts the square: measure the side with less than half of it (the square is
        // symmetric about its centre, where h is halfway), the other is the rest.
        const double level = double(first_band + 1);
        const bool below_smaller = level - f_min <= f_max - level;
        ColumnPolygon part;
        detail::squarePart(f, level, below_smaller, part);
        const int small = below_smaller ? first_band : first_band + 1;
        if (small >= lo && small <= hi) {
            fromPolygon(part);
            visit(small, piece);
        }
        const int rest = below_smaller ? first_band + 1 : first_band;
        if (rest >= lo && rest <= hi) {
            fromSums(2.0 - part.twice_area, 3.0 - part.moment_a, 3.0 - part.moment_b);
            visit(rest, piece);
        }
    } else if (bands > 3) {  // rounding put the square's span a hair over 2: cut band by band
        ColumnPolygon square;
        for (int c = 0; c < 4; ++c) square.add(detail::kSquareA[c], detail::kSquareB[c], f[c]);
        for (int k = std::max(lo, first_band); k <= std::min(hi, last_band); ++k) {
            ColumnPolygon above, band;
            detail::clipAtLevel(square, double(k), false, above);
            detail::clipAtLevel(above, double(k) + 1.0, true, band);
            if (band.n == 0) continue;
            band.measure();
            fromPolygon(band);
            visit(k, piece);
        }
    } else if (bands == 3) {
        ColumnPolygon bottom, top;
        detail::squarePart(f, double(first_band + 1), true, bottom);
        detail::squarePart(f, double(first_band + 2), false, top);
        if (first_band >= lo && first_band <= hi) {
            fromPolygon(bottom);
            visit(first_band, piece);
        }
        if (first_band + 1 >= lo && first_band + 1 <= hi) {
            fromSums(2.0 - bottom.twice_area - top.twice_area, 3.0 - bottom.moment_a - top.moment_a,
                     3.0 - bottom.moment_b - top.moment_b);
            visit(first_band + 1, piece);
        }
        if (last_band >= lo && last_band <= hi) {
            fromPolygon(top);
            visit(last_band, piece);
        }
    }
    if (double(last_band + 1) == f_max && last_band + 1 >= lo && last_band + 1 <= hi) {
        touchAt(f_max);
        visit(last_band + 1, piece);
    }
}

}  // namespace hyvox::attributes
