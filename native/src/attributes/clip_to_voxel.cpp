// SPDX-License-Identifier: GPL-3.0-or-later
#include "attributes/clip_to_voxel.h"

#include <algorithm>
#include <cmath>

namespace hyvox::attributes {
namespace {

constexpr int kMaxCorners = Polygon::kMaxCorners;

// Keeps the part with sign * (x[Axis] - bound) >= 0. A crossing point is placed exactly on
// the plane; a corner on the plane is kept as it is (no crossing is added for it). Each
// corner's signed distance is computed once (the same expression for both edges it ends).
template <int Axis>
void clipPlane(const Polygon& in, Polygon& out, double bound, double sign) {
    double distance[kMaxCorners];
    for (int e = 0; e < in.n; ++e) distance[e] = sign * (in.p[std::size_t(e)][Axis] - bound);
    out.n = 0;
    for (int e = 0; e < in.n; ++e) {
        const int next = e + 1 < in.n ? e + 1 : 0;
        const Point& cur = in.p[std::size_t(e)];
        const Point& nxt = in.p[std::size_t(next)];
        const double dc = distance[e], dn = distance[next];
        if (dc >= 0 && out.n < kMaxCorners) out.p[std::size_t(out.n++)] = cur;
        if (((dc > 0 && dn < 0) || (dc < 0 && dn > 0)) && out.n < kMaxCorners) {
            const double t = dc / (dc - dn);
            Point& point = out.p[std::size_t(out.n++)];
            for (std::size_t a = 0; a < 3; ++a) point[a] = cur[a] + (nxt[a] - cur[a]) * t;
            point[Axis] = bound;
        }
    }
}

// A plane that has the whole polygon on its kept side leaves it as it is (no corner is
// dropped, no crossing added), and one that has it all on the other side leaves nothing:
// those clips are decided from the polygon's extent and skipped, with the same result.
template <int Axis>
const Polygon& clipSlabAlong(const Polygon& in, Polygon& scratch, double lo, double hi) {
    double from = in.p[0][Axis], to = from;
    for (int c = 1; c < in.n; ++c) {
        from = std::min(from, in.p[std::size_t(c)][Axis]);
        to = std::max(to, in.p[std::size_t(c)][Axis]);
    }
    if (to < lo || from > hi) {
        scratch.n = 0;
        return scratch;
    }
    const bool cut_lo = from<lo, cut_hi = to> hi;
    if (cut_lo && cut_hi) {
        Polygon between;
        clipPlane<Axis>(in, between, lo, 1.0);
        clipPlane<Axis>(between, scratch, hi, -1.0);
    } else if (cut_lo) {
        clipPlane<Axis>(in, scratch, lo, 1.0);
    } else if (cut_hi) {
        clipPlane<Axis>(in, scratch, hi, -1.0);
    } else {
        return in;
    }
    return scratch;
}

Point sub(const Point& a, const Point& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(const Point& a, const Point& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

}  // namespace

const Polygon& clipSlab(const Polygon& in, Polygon& scratch, int axis, double lo, double hi) {
    switch (axis) {
        case 0: return clipSlabAlong<0>(in, scratch, lo, hi);
        case 1: return clipSlabAlong<1>(in, scratch, lo, hi);
        default: return clipSlabAlong<2>(in, scratch, lo, hi);
    }
}

bool clipTriangleToVoxel(const std::array<Point, 3>& corners, const std::array<int, 3>& voxel,
                         const TriangleFrame& frame, ClippedPiece& out, double margin) {
    Polygon whole, x_slab, xy_column, box;
    whole.n = 3;
    std::copy(corners.begin(), corners.end(), whole.p.begin());
    const Polygon& a = clipSlab(whole, x_slab, 0, double(voxel[0]) - margin, double(voxel[0]) + 1.0 + margin);
    if (a.n == 0) return false;
    const Polygon& b = clipSlab(a, xy_column, 1, double(voxel[1]) - margin, double(voxel[1]) + 1.0 + margin);
    if (b.n == 0) return false;
    const Polygon& c = clipSlab(b, box, 2, double(voxel[2]) - margin, double(voxel[2]) + 1.0 + margin);
    if (c.n == 0) return false;
    measurePiece(c, frame, out);
    return true;
}

void measurePiece(const Polygon& a, const TriangleFrame& frame, ClippedPiece& out) {
    measurePiece(a, frame.projectionAxes()[0], frame.projectionAxes()[1], frame.projectedAreaScale(), out);
}

void measurePiece(const Polygon& a, int u, int v, double scale, ClippedPiece& out) {
    // Area and centroid by a fan from the first corner (the piece is convex and lies in the
    // triangle's plane): each fan triangle's area from its projection on the triangle's
    // dominant plane (one 2D cross product, scaled), no square root per piece.
    double area = 0;
    Point moment{0, 0, 0};
    const Point& p0 = a.p[0];
    for (int k = 1; k + 1 < a.n; ++k) {
        const Point& p1 = a.p[std::size_t(k)];
        const Point& p2 = a.p[std::size_t(k + 1)];
        const double cross = (p1[u] - p0[u]) * (p2[v] - p0[v]) - (p1[v] - p0[v]) * (p2[u] - p0[u]);
        const double tri = scale * cross;
        area += tri;
        for (std::size_t d = 0; d < 3; ++d) moment[d] += tri * (p0[d] + p1[d] + p2[d]);
    }
    out.area = std::max(area, 0.0);  // a touch's rounding may leave it a hair below zero
    if (area >= kTouchArea) {
        // Each fan triangle's centroid is its corners' sum / 3: one division for all three axes.
        const double inverse = 1.0 / (3.0 * area);
        for (std::size_t d = 0; d < 3; ++d) out.centroid[d] = moment[d] * inverse;
        return;
    }
    // A touch: the midpoint of the two points farthest apart (a point: itself).
    int best_i = 0, best_j = 0;
    double best = -1;
    for (int i = 0; i < a.n; ++i)
        for (int j = 0; j < a.n; ++j) {
            const Point d = sub(a.p[std::size_t(i)], a.p[std::size_t(j)]);
            const double dist = dot(d, d);
            if (dist > best) {
                best = dist;
                best_i = i;
                best_j = j;
            }
        }
    for (std::size_t d = 0; d < 3; ++d)
        out.centroid[d] = 0.5 * (a.p[std::size_t(best_i)][d] + a.p[std::size_t(best_j)][d]);
}

TriangleFrame::TriangleFrame(const std::array<Point, 3>& corners) : origin_(corners[0]) {
    const Point v0 = sub(corners[1], corners[0]), v1 = sub(corners[2], corners[0]);
    const double d00 = dot(v0, v0), d01 = dot(v0, v1), d11 = dot(v1, v1);
    const double denom = d00 * d11 - d01 * d01;
    flat_ = !(denom > 0);
    // Barycentrics v, w are linear in the point: v = (d11 d20 - d01 d21) / denom with
    // d2c = (p - origin) . vc, i.e. (p - origin) . gradient.
    for (std::size_t a = 0; a < 3; ++a) {
        gradient_v_[a] = flat_ ? 0.0 : (d11 * v0[a] - d01 * v1[a]) / denom;
        gradient_w_[a] = flat_ ? 0.0 : (d00 * v1[a] - d01 * v0[a]) / denom;
    }
    const Point n{v0[1] * v1[2] - v0[2] * v1[1], v0[2] * v1[0] - v0[0] * v1[2], v0[0] * v1[1] - v0[1] * v1[0]};
    const double length = std::sqrt(dot(n, n));
    for (std::size_t a = 0; a < 3; ++a) unit_normal_[a] = length > 0 ? n[a] / length : 0.0;
    // The dominant axis w and the cyclic pair (u, v) after it: the (u, v) cross product of
    // two edges is their 3D cross product's w component, n_w / |n| of its length.
    const Point an{std::fabs(n[0]), std::fabs(n[1]), std::fabs(n[2])};
    const int w = (an[0] >= an[1] && an[0] >= an[2]) ? 0 : (an[1] >= an[2] ? 1 : 2);
    projection_axes_ = {w == 2 ? 0 : w + 1, w == 0 ? 2 : w - 1};
    projected_area_scale_ = n[std::size_t(w)] != 0 ? 0.5 * length / n[std::size_t(w)] : 0.0;
}

}  // namespace hyvox::attributes
