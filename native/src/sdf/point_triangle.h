// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The exact distance from points to one triangle, in voxel space and double precision.
//
// The triangle is set in its own orthonormal frame: u along its longest edge, h along its
// normal, v across. A point at (u, v, h) is then h² + (the distance from (u, v) to the flat
// triangle)² away, squared; that flat distance is 0 when (u, v) lies inside, else the least of
// the three distances to the edges (segments). The two cases agree on the boundary between
// them, so a rounding error in deciding the case moves the answer by a rounding error only, and
// the formula has no branches: a row of points vectorises. Along a row (x, y fixed, z in whole
// steps) u, v and h and the edges' dot products are linear in z.
//
// The normal comes from the two shortest edges (core/triangle_normal.h), so slivers keep their
// plane. A triangle without one in voxel space (a segment or a point) gets any frame whose u
// runs along its longest edge: its "flat triangle" is that segment (or point), exactly.
#include <algorithm>
#include <array>
#include <cmath>

#include "core/avx2_clones.h"
#include "core/triangle_normal.h"

// Loops over minDistance2Along run four doubles wide instead of two in the AVX2 copies
// (HYVOX_AVX2_CLONES_GCC) of their callers.
namespace hyvox::sdf {

using Vec3 = std::array<double, 3>;

inline double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline Vec3 minus(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline Vec3 scaled(const Vec3& a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }
inline Vec3 unit(const Vec3& a) { return scaled(a, 1.0 / std::sqrt(dot(a, a))); }
// How far a point is from the interval [lo, hi] (0 inside it).
inline double gap(double point, double lo, double hi) { return std::max({lo - point, 0.0, point - hi}); }
inline Vec3 centroidOf(const std::array<Vec3, 3>& c) {
    return {(c[0][0] + c[1][0] + c[2][0]) / 3.0, (c[0][1] + c[1][1] + c[2][1]) / 3.0,
            (c[0][2] + c[1][2] + c[2][2]) / 3.0};
}

// A triangle laid flat in its own frame (u, v): corners (0, 0), (bu, 0), (cu, cv), edges
// (e0, e1, e2) from each corner to the next with their inverse squared lengths, and the
// orientation (+1 counterclockwise, -1 clockwise, 0 for a segment or a point).
struct Flat {
    double bu, cu, cv, e0u, e0v, e1u, e1v, e2u, e2v, l0, l1, l2, turn;

    // The squared distance from the point at (u, v) in the triangle's plane and h above it.
    double distance2(double u, double v, double h) const {
        // From each edge's first corner: (0, 0), (bu, 0), (cu, cv).
        const double p0u = u, p0v = v, p1u = u - bu, p1v = v, p2u = u - cu, p2v = v - cv;
        const double t0 = std::min(std::max((p0u * e0u + p0v * e0v) * l0, 0.0), 1.0);
        const double t1 = std::min(std::max((p1u * e1u + p1v * e1v) * l1, 0.0), 1.0);
        const double t2 = std::min(std::max((p2u * e2u + p2v * e2v) * l2, 0.0), 1.0);
        const double r0u = p0u - t0 * e0u, r0v = p0v - t0 * e0v;
        const double r1u = p1u - t1 * e1u, r1v = p1v - t1 * e1v;
        const double r2u = p2u - t2 * e2u, r2v = p2v - t2 * e2v;
        const double edges = std::min(r0u * r0u + r0v * r0v, std::min(r1u * r1u + r1v * r1v, r2u * r2u + r2v * r2v));
        // Left of edge c: its cross product with the point's offset is positive.
        const bool inside = (turn * (e0u * p0v - e0v * p0u) > 0) & (turn * (e1u * p1v - e1v * p1u) > 0) &
            (turn * (e2u * p2v - e2v * p2u) > 0);
        return h * h + (inside ? 0.0 : edges);
    }
};

class DistanceTriangle {
public:
    explicit DistanceTriangle(const std::array<Vec3, 3>& corners) {
        corner = corners;
        // The frame: u along the longest edge, h the unit normal, v = h × u.
        int longest = 0;
        double longest2 = -1;
        Vec3 edges[3];
        for (int i = 0; i < 3; ++i) {
            edges[i] = minus(corners[i == 2 ? 0 : i + 1], corners[i]);
            const double length2 = dot(edges[i], edges[i]);
            if (length2 > longest2) longest2 = length2, longest = i;
        }
        origin = corners[longest];
        Vec3 n = stableTriangleNormal(corners[0], corners[1], corners[2]);
        const double n_length = std::sqrt(dot(n, n));
        if (longest2 > 0) {
            u_axis = scaled(edges[longest], 1.0 / std::sqrt(longest2));
        } else {
            u_axis = {1, 0, 0};  // a point: any frame
        }
        if (n_length > 0) {
            n = scaled(n, 1.0 / n_length);
        } else {  // a segment or a point: any normal across u
            const Vec3 other = std::fabs(u_axis[0]) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
            n = triangle_normal_detail::cross(u_axis, other);
            n = scaled(n, 1.0 / std::sqrt(dot(n, n)));
        }
        Vec3 v = triangle_normal_detail::cross(n, u_axis);
        v_axis = scaled(v, 1.0 / std::sqrt(dot(v, v)));
        h_axis = n;
        // The flat triangle, starting at the longest edge's first corner (0, 0): its corners
        // and edges in (u, v), with the edges' inverse squared lengths and inward normals.
        for (int c = 0; c < 3; ++c) {
            const Vec3 q = minus(corners[(longest + c) % 3], origin);
            flat_u[c] = c == 0 ? 0.0 : dot(q, u_axis);
            flat_v[c] = c == 0 ? 0.0 : dot(q, v_axis);
        }
        flat_v[1] = 0.0;  // the longest edge is the u axis itself
        for (int c = 0; c < 3; ++c) {
            const int next = c == 2 ? 0 : c + 1;
            edge_u[c] = flat_u[next] - flat_u[c];
            edge_v[c] = flat_v[next] - flat_v[c];
            const double length2 = edge_u[c] * edge_u[c] + edge_v[c] * edge_v[c];
            inverse_length2[c] = length2 > 0 ? 1.0 / length2 : 0.0;
        }
        // Inside is to the left of every edge when the flat triangle runs counterclockwise
        // (v of its third corner above the u axis), else to the right; a flat triangle of no
        // area (a segment) has no inside.
        orientation = flat_v[2] > 0 ? 1.0 : flat_v[2] < 0 ? -1.0 : 0.0;
    }

    // The squared distances from the points (x, y, z + n), n < count, each taken as the least
    // of itself and best[n]. Everything the loop reads is in locals (nothing through `this`,
    // which `best` might alias), so it vectorises.
    void minDistance2Along(double x, double y, double z, int count, double* best) const {
        const Vec3 q{x - origin[0], y - origin[1], z - origin[2]};
        const double u0 = dot(q, u_axis), uz = u_axis[2];
        const double v0 = dot(q, v_axis), vz = v_axis[2];
        const double h0 = dot(q, h_axis), hz = h_axis[2];
        const Flat flat = this->flat();
        for (int n = 0; n < count; ++n) {
            const double step = n;  // converted, not accumulated: exact, and it vectorises
            best[n] = std::min(best[n], flat.distance2(u0 + step * uz, v0 + step * vz, h0 + step * hz));
        }
    }

    double distance2(const Vec3& p) const {
        double best = HUGE_VAL;
        minDistance2Along(p[0], p[1], p[2], 1, &best);
        return best;
    }

    Flat flat() const {
        return {flat_u[1], flat_u[2], flat_v[2],          edge_u[0],          edge_v[0],          edge_u[1],  edge_v[1],
                edge_u[2], edge_v[2], inverse_length2[0], inverse_length2[1], inverse_length2[2], orientation};
    }

    std::array<Vec3, 3> corner;
    Vec3 h_axis;  // the unit normal (any unit vector across a triangle without a plane)

private:
    friend class DistanceTriangles4;
    Vec3 origin, u_axis, v_axis;
    double flat_u[3], flat_v[3], edge_u[3], edge_v[3], inverse_length2[3];
    double orientation;
};

// Up to four triangles side by side, each field four wide, so that one point's distances to
// them compute as one vector (a lane without a triangle repeats the last one).
class DistanceTriangles4 {
public:
    static constexpr int kLanes = 4;
    // triangles[0..count), 1 <= count <= 4.
    DistanceTriangles4(const DistanceTriangle* triangles, int count) {
        for (int lane = 0; lane < kLanes; ++lane) {
            const DistanceTriangle& t = triangles[std::min(lane, count - 1)];
            for (int a = 0; a < 3; ++a) {
                frame_[kOrigin + a][lane] = t.origin[a];
                frame_[kU + a][lane] = t.u_axis[a];
                frame_[kV + a][lane] = t.v_axis[a];
                frame_[kH + a][lane] = t.h_axis[a];
            }
            const Flat flat = t.flat();
            for (int f = 0; f < kFlatFields; ++f) flat_[f][lane] = flat.*kFlat[f];
        }
    }

    // The least of `best` and the squared distances from (x, y, z) to the triangles.
    double minDistance2(double x, double y, double z, double best) const {
        double out[kLanes];
        for (int lane = 0; lane < kLanes; ++lane) {
            const double qx = x - frame_[kOrigin][lane], qy = y - frame_[kOrigin + 1][lane],
                         qz = z - frame_[kOrigin + 2][lane];
            auto along = [&](int axis) {
                return qx * frame_[axis][lane] + qy * frame_[axis + 1][lane] + qz * frame_[axis + 2][lane];
            };
            Flat flat;
            for (int f = 0; f < kFlatFields; ++f) flat.*kFlat[f] = flat_[f][lane];
            out[lane] = flat.distance2(along(kU), along(kV), along(kH));
        }
        return std::min({best, out[0], out[1], out[2], out[3]});
    }

private:
    // The frames' rows: the origin and the u, v and h axes, x y z each.
    enum : int { kOrigin = 0, kU = 3, kV = 6, kH = 9, kFrameRows = 12 };
    double frame_[kFrameRows][kLanes];
    // Flat's fields, each a row of its own too (rows of lanes vectorise; Flats side by side do not).
    static constexpr int kFlatFields = 13;
    static constexpr double Flat::*kFlat[kFlatFields] = {&Flat::bu,  &Flat::cu,  &Flat::cv,  &Flat::e0u, &Flat::e0v,
                                                         &Flat::e1u, &Flat::e1v, &Flat::e2u, &Flat::e2v, &Flat::l0,
                                                         &Flat::l1,  &Flat::l2,  &Flat::turn};
    double flat_[kFlatFields][kLanes];
};

}  // namespace hyvox::sdf
