// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Voxel-space coordinates of geometry far outside the grid are clamped before they become
// integers (so the conversion stays defined). Every method clamps with this one bound, so
// the part of a far-away triangle that is clipped to the grid is equally approximate in all.

namespace hyvox {

inline double clampCoord(double x) { return x < -1.0e9 ? -1.0e9 : (x > 1.0e9 ? 1.0e9 : x); }

}  // namespace hyvox
