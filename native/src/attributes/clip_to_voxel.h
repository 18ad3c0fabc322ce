// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The part of a triangle inside one voxel's closed box, by Sutherland-Hodgman clipping in
// double (voxel space: voxel (i,j,k) is [i, i+1] x [j, j+1] x [k, k+1]). Points on a face
// count as inside, so a triangle lying on a voxel face belongs to both voxels, and a touch
// (an edge or corner on the box) is kept with no area.
#include <array>

namespace hyvox::attributes {

using Point = std::array<double, 3>;

// Clipped areas below this count as a touch (voxel units²).
constexpr double kTouchArea = 1e-14;
// Weight added to every piece, so touches count (DESIGN.md, "Attributes").
constexpr double kAreaEpsilon = 1e-6;

struct ClippedPiece {
    double area = 0;    // voxel units²
    Point centroid{};   // the area centroid; a touch: the midpoint of its two farthest points
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
// at lo first: clipping a triangle slab by slab (x, then y, then z) gives exactly the
// polygons clipTriangleToVoxel gives box by box. The result is `in` itself when both planes
// keep all of it, else written to `scratch` (n = 0: nothing is left).
const Polygon& clipSlab(const Polygon& in, Polygon& scratch, int axis, double lo, double hi);

// A triangle's set-up for all its pieces: barycentrics, its unit normal, and the scale from
// areas projected on its dominant plane to its own.
class TriangleFrame {
public:
    explicit TriangleFrame(const std::array<Point, 3>& corners);
    // Barycentrics of `point` (in the triangle's plane) clamped to [0, 1] and renormalised.
    std::array<double, 3> barycentrics(const Point& point) const;
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

// False when the triangle misses the box (grown by `margin` voxels on every side).
bool clipTriangleToVoxel(const std::array<Point, 3>& corners, const std::array<int, 3>& voxel,
                         const TriangleFrame& frame, ClippedPiece& out, double margin = 0.0);

}  // namespace hyvox::attributes
