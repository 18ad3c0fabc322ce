// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The exact distance from a point to a triangle in double, by an algorithm the library does
// not use: the oracle of the sdf's distances (tests/native/test_sdf.cpp, tests/fuzz/fuzz_sdf.cpp).
// Header-only, so the fuzz build takes it without the test support library.
#include <algorithm>
#include <array>
#include <cmath>

namespace hyvox::test::closest_point {

using Vec3 = std::array<double, 3>;

inline Vec3 sub(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline Vec3 along(const Vec3& a, const Vec3& d, double t) {
    return {a[0] + t * d[0], a[1] + t * d[1], a[2] + t * d[2]};
}
inline double length(const Vec3& a) { return std::sqrt(dot(a, a)); }

// The distance from p to segment ab (a point when a = b).
inline double pointSegmentDistance(const Vec3& p, const Vec3& a, const Vec3& b) {
    const Vec3 ab = sub(b, a);
    const double length2 = dot(ab, ab);
    const double t = length2 > 0 ? std::clamp(dot(sub(p, a), ab) / length2, 0.0, 1.0) : 0.0;
    return length(sub(p, along(a, ab, t)));
}

// Ericson, Real-Time Collision Detection 5.1.5: the closest point of triangle abc to p, by
// its Voronoi regions (an algorithm the library does not use).
inline double voronoiDistance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 ab = sub(b, a), ac = sub(c, a), ap = sub(p, a);
    const double d1 = dot(ab, ap), d2 = dot(ac, ap);
    if (d1 <= 0 && d2 <= 0) return length(ap);
    const Vec3 bp = sub(p, b);
    const double d3 = dot(ab, bp), d4 = dot(ac, bp);
    if (d3 >= 0 && d4 <= d3) return length(bp);
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return length(sub(p, along(a, ab, d1 / (d1 - d3))));
    const Vec3 cp = sub(p, c);
    const double d5 = dot(ab, cp), d6 = dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) return length(cp);
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return length(sub(p, along(a, ac, d2 / (d2 - d6))));
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0)
        return length(sub(p, along(b, sub(c, b), (d4 - d3) / ((d4 - d3) + (d5 - d6)))));
    const double denom = 1.0 / (va + vb + vc);
    const Vec3 q = along(along(a, ab, vb * denom), ac, vc * denom);
    return length(sub(p, q));
}

// The distance from p to triangle abc. A triangle without area (coincident corners) divides 0
// by 0 in voronoiDistance: its edges, as segments, give the distance.
inline double pointTriangleDistance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    const double edges =
        std::min({pointSegmentDistance(p, a, b), pointSegmentDistance(p, b, c), pointSegmentDistance(p, c, a)});
    const double voronoi = voronoiDistance(p, a, b, c);
    return std::isnan(voronoi) ? edges : std::min(voronoi, edges);
}

}  // namespace hyvox::test::closest_point
