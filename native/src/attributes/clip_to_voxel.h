// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The part of a triangle inside one voxel's closed box, by Sutherland-Hodgman clipping in
// double (voxel space: voxel (i,j,k) is [i, i+1] x [j, j+1] x [k, k+1]). Points on a face
// count as inside, so a triangle lying on a voxel face belongs to both voxels, and a touch
// (an edge or corner on the box) is kept with no area.
#include <algorithm>
#include <array>

namespace hyvox::attributes {

using Point = std::array<double, 3>;

// Clipped areas below this count as a touch (voxel units²).
constexpr double kTouchArea = 1e-14;
// Weight added to every piece, so touches count (docs/design.md, "Attributes").
constexpr double kAreaEpsilon = 1e-6;

struct ClippedPiece {
    double area = 0;   // voxel units²
    Point centroid{};  // the area centroid; a touch: the midpoint of its two farthest points
};

// A voxel's box grown by this on every side finds the touches that clipping to the exact box
// loses to rounding (a triangle through a box corner: crossing points are rounded).
constexpr double kTouchMargin = 1e-9;

// A convex polygon being clipped (a triangle clipped by 6 half-spaces has at most 9 corners;
// room to spare for the duplicate points exact touches leave).
struct Polygon {
    static constexpr int kMaxCorners = 16;
    std::array<Point, kMaxCorners> p;
    int n = 0;
};

// The part of `in` between the planes x[axis] = lo and x[axis] = hi (inclusive), clipped
// at lo first (clipTriangleToVoxel's steps). The result is `in` itself when both planes keep
// all of it, else written to `scratch` (n = 0: nothing is left).
const Polygon& clipSlab(const Polygon& in, Polygon& scratch, int axis, double lo, double hi);

// A triangle's set-up for all its pieces: barycentrics, its unit normal, and the scale from
// areas projected on its dominant plane to its own.
class TriangleFrame {
public:
    explicit TriangleFrame(const std::array<Point, 3>& corners);
    // Barycentrics of `point` (in the triangle's plane) clamped to [0, 1] and renormalised.
    // (Inline: it runs once per clipped piece.)
    std::array<double, 3> barycentrics(const Point& point) const {
        if (flat_) return {1.0 / 3, 1.0 / 3, 1.0 / 3};  // a sliver flat to rounding: its centre
        const Point d{point[0] - origin_[0], point[1] - origin_[1], point[2] - origin_[2]};
        const double v = d[0] * gradient_v_[0] + d[1] * gradient_v_[1] + d[2] * gradient_v_[2];
        const double w = d[0] * gradient_w_[0] + d[1] * gradient_w_[1] + d[2] * gradient_w_[2];
        const double u = 1.0 - v - w;
        // A centroid of a piece of the triangle is inside it: renormalise only what rounding
        // put outside.
        if (u >= 0 && v >= 0 && w >= 0 && u <= 1 && v <= 1 && w <= 1) return {u, v, w};
        std::array<double, 3> bary{std::clamp(u, 0.0, 1.0), std::clamp(v, 0.0, 1.0), std::clamp(w, 0.0, 1.0)};
        const double scale = 1.0 / (bary[0] + bary[1] + bary[2]);
        for (double& b : bary) b *= scale;
        return bary;
    }
    const Point& unitNormal() const { return unit_normal_; }
    // The two axes after the dominant normal axis (cyclic), and half the factor from a
    // cross product in them (same orientation as the triangle) to the area in 3D.
    const std::array<int, 2>& projectionAxes() const { return projection_axes_; }
    double projectedAreaScale() const { return projected_area_scale_; }

private:
    Point origin_;
    Point gradient_v_, gradient_w_;  // of the second and third barycentric
    bool flat_ = false;
    Point unit_normal_;
    std::array<int, 2> projection_axes_{0, 1};
    double projected_area_scale_ = 0;
};

// Area and centroid of a clipped polygon (n > 0) of the triangle `frame` describes.
void measurePiece(const Polygon& polygon, const TriangleFrame& frame, ClippedPiece& out);
// The same with the projection given: the polygon's cross products in axes (u, v) times
// `projected_area_scale` are areas (TriangleFrame::projectionAxes, projectedAreaScale).
void measurePiece(const Polygon& polygon, int u, int v, double projected_area_scale, ClippedPiece& out);

// False when the triangle misses the box (grown by `margin` voxels on every side).
bool clipTriangleToVoxel(const std::array<Point, 3>& corners, const std::array<int, 3>& voxel,
                         const TriangleFrame& frame, ClippedPiece& out, double margin = 0.0);

}  // namespace hyvox::attributes
