// SPDX-License-Identifier: GPL-3.0-or-later
#include "attributes/clip_to_voxel.h"

#include <algorithm>
#include <cmath>

namespace hyvox::attributes {
namespace {

constexpr int kMaxCorners = Polygon::kMaxCorners;

// Keeps the part with sign * (x[axis] - bound) >= 0. A crossing point is placed exactly on
// the plane; a corner on the plane is kept as it is (no crossing is added for it).
void clipPlane(const Polygon& in, Polygon& out, int axis, double bound, double sign) {
    out.n = 0;
    for (int e = 0; e < in.n; ++e) {
        const Point& cur = in.p[std::size_t(e)];
        const Point& nxt = in.p[std::size_t(e + 1 < in.n ? e + 1 : 0)];
        const double dc = sign * (cur[std::size_t(axis)] - bound);
        const double dn = sign * (nxt[std::size_t(axis)] - bound);
        if (dc >= 0 && out.n < kMaxCorners) out.p[std::size_t(out.n++)] = cur;
        if (((dc > 0 && dn < 0) || (dc < 0 && dn > 0)) && out.n < kMaxCorners) {
            const double t = dc / (dc - dn);
            Point point;
            for (std::size_t a = 0; a < 3; ++a) point[a] = cur[a] + (nxt[a] - cur[a]) * t;
            point[std::size_t(axis)] = bound;
            out.p[std::size_t(out.n++)] = point;
        }
    }
}

Point sub(const Point& a, const Point& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(const Point& a, const Point& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

}  // namespace

void clipSlab(const Polygon& in, Polygon& out, int axis, double lo, double hi) {
    Polygon between;
    clipPlane(in, between, axis, lo, 1.0);
    if (between.n == 0) {
        out.n = 0;
        return;
    }
    clipPlane(between, out, axis, hi, -1.0);
}

bool clipTriangleToVoxel(const std::array<Point, 3>& corners, const std::array<int, 3>& voxel, ClippedPiece& out,
                         double margin) {
    Polygon a, b;
    a.n = 3;
    std::copy(corners.begin(), corners.end(), a.p.begin());
    for (int axis = 0; axis < 3; ++axis) {
        clipSlab(a, b, axis, double(voxel[std::size_t(axis)]) - margin, double(voxel[std::size_t(axis)]) + 1.0 + margin);
        if (b.n == 0) return false;
        a = b;
    }
    measurePiece(a, out);
    return true;
}

void measurePiece(const Polygon& a, ClippedPiece& out) {
    // Area and centroid by a fan from the first corner (the piece is convex).
    double area = 0;
    Point moment{0, 0, 0};
    const Point& p0 = a.p[0];
    for (int k = 1; k + 1 < a.n; ++k) {
        const Point u = sub(a.p[std::size_t(k)], p0), v = sub(a.p[std::size_t(k + 1)], p0);
        const Point c{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
        const double tri = 0.5 * std::sqrt(dot(c, c));
        area += tri;
        for (std::size_t d = 0; d < 3; ++d) moment[d] += tri * (p0[d] + a.p[std::size_t(k)][d] + a.p[std::size_t(k + 1)][d]) / 3.0;
    }
    out.area = area;
    if (area >= kTouchArea) {
        for (std::size_t d = 0; d < 3; ++d) out.centroid[d] = moment[d] / area;
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
    for (std::size_t d = 0; d < 3; ++d) out.centroid[d] = 0.5 * (a.p[std::size_t(best_i)][d] + a.p[std::size_t(best_j)][d]);
}

TriangleFrame::TriangleFrame(const std::array<Point, 3>& corners)
    : origin_(corners[0]), v0_(sub(corners[1], corners[0])), v1_(sub(corners[2], corners[0])) {
    d00_ = dot(v0_, v0_);
    d01_ = dot(v0_, v1_);
    d11_ = dot(v1_, v1_);
    denom_ = d00_ * d11_ - d01_ * d01_;
    const Point n{v0_[1] * v1_[2] - v0_[2] * v1_[1], v0_[2] * v1_[0] - v0_[0] * v1_[2], v0_[0] * v1_[1] - v0_[1] * v1_[0]};
    const double length = std::sqrt(dot(n, n));
    for (std::size_t a = 0; a < 3; ++a) unit_normal_[a] = length > 0 ? n[a] / length : 0.0;
}

std::array<double, 3> TriangleFrame::barycentrics(const Point& point) const {
    if (!(denom_ > 0)) return {1.0 / 3, 1.0 / 3, 1.0 / 3};  // a sliver flat to rounding: its centre
    const Point v2 = sub(point, origin_);
    const double d20 = dot(v2, v0_), d21 = dot(v2, v1_);
    const double v = (d11_ * d20 - d01_ * d21) / denom_;
    const double w = (d00_ * d21 - d01_ * d20) / denom_;
    std::array<double, 3> bary{std::clamp(1.0 - v - w, 0.0, 1.0), std::clamp(v, 0.0, 1.0), std::clamp(w, 0.0, 1.0)};
    const double sum = bary[0] + bary[1] + bary[2];
    for (double& b : bary) b /= sum;
    return bary;
}

}  // namespace hyvox::attributes
