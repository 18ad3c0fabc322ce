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

// False when the triangle misses the box (grown by `margin` voxels on every side).
bool clipTriangleToVoxel(const std::array<Point, 3>& corners, const std::array<int, 3>& voxel, ClippedPiece& out,
                         double margin = 0.0);

// Barycentrics of `point` (in the triangle's plane) clamped to [0, 1] and renormalised.
std::array<double, 3> barycentrics(const std::array<Point, 3>& corners, const Point& point);

}  // namespace hyvox::attributes
