// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A float atan2 that vectorises (libm's does not), for the loops over the open edges' sheets
// (sheet_sum.cpp) and over a box's near triangles (solid_angle_sum.cpp). Include it only
// from files built with -fno-math-errno -fno-trapping-math (solid/CMakeLists.txt).
#include <algorithm>
#include <cmath>

namespace hyvox::solid::floats {

// atan2(y, x) in (-π, π], from atan on [0, 1] by Abramowitz & Stegun 4.4.49 (|error| <= 2e-8).
// Written with selects, not branches, so that it vectorises.
inline float arctangent2(float y, float x) {
    const float abs_x = std::fabs(x), abs_y = std::fabs(y);
    const float low = std::min(abs_x, abs_y), high = std::max(abs_x, abs_y);
    const float r = low / std::max(high, 1e-30f);  // (0, 0) gives 0, as std::atan2 does
    const float s = r * r;
    float p = 0.0028662257f;
    p = p * s - 0.0161657367f;
    p = p * s + 0.0429096138f;
    p = p * s - 0.0752896400f;
    p = p * s + 0.1065626393f;
    p = p * s - 0.1420889944f;
    p = p * s + 0.1999355085f;
    p = p * s - 0.3333314528f;
    float angle = r + r * s * p;
    angle = abs_y > abs_x ? float(M_PI / 2) - angle : angle;
    angle = x < 0 ? float(M_PI) - angle : angle;
    return y < 0 ? -angle : angle;
}

}  // namespace hyvox::solid::floats
