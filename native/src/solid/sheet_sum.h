// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The summed winding numbers of the open edges' sheets near one box (solid/smooth_winding.h),
// at many points of that box: the per-voxel inner loop of the open-mesh winding numbers.
//
// The sheets are stored as arrays of floats relative to the box's corner (structure of
// arrays), so the compiler vectorises the loop over them; the arctangent is a polynomial
// (Abramowitz & Stegun 4.4.49, error below 2e-8 rad before float rounding) instead of
// libm's atan2, which does not vectorise. Float is enough with the formula arranged against
// cancellation (sheet_sum.cpp): a sum of a thousand sheets is within about 1e-5 of the double
// solid angles (tests/native/test_solid.cpp compares it with each sheet as two tall
// triangles), far inside the margins the smooth part is used with (0.02 and 0.06).
#include <array>
#include <vector>

#include "solid/gradient_bound.h"

namespace hyvox::solid {

class SheetSum {
public:
    // A column through a point passing this close to an edge in xy (voxels) makes at() NaN.
    static constexpr float kTie = 1e-3f;
    // The sheets of `sheets` (above their edges, or below them when `upward`), seen from points
    // near `origin`, an integer point of voxel space.
    void assign(const std::vector<GradientBound::Sheet>& sheets, bool upward, const std::array<double, 3>& origin);
    // Σ excess · (the sheet's winding number at q), or NaN when the column through q passes
    // within 1e-3 voxel of a sheet's edge in xy, where the solid angle jumps and the rays'
    // tie-breaking decides instead.
    double at(const std::array<double, 3>& q) const;
    // at() at the points (x, y, z[n]) of one vertical line, n < count, into out[n]: the terms
    // that depend on x and y alone computed once for the line. Equal to at() bit for bit.
    void atColumn(double x, double y, const double* z, int count, double* out) const;
    std::size_t size() const { return count_; }

private:
    std::size_t count_ = 0;
    float up_ = 1.0f;
    std::array<double, 3> origin_{};
    // Per sheet, padded to a multiple of the lane count with sheets of weight 0: the edge's
    // start a (relative to origin_), its direction e = b - a, 1 / |e_xy|² (0 for a vertical
    // edge), and excess / 2π.
    std::vector<float> ax_, ay_, az_, ex_, ey_, ez_, inverse_length2_, weight_;
    mutable std::vector<float> terms_;  // at()'s per-sheet terms (one SheetSum per thread)
    // atColumn()'s per-sheet parts of the line, those that depend on x and y alone
    // (sheet_sum.cpp, LineParts).
    mutable std::vector<float> uxy2_, vxy2_, uv_, eu_, ev_, poison_;
};

}  // namespace hyvox::solid
