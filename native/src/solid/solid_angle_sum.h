// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The summed solid angles (over 4π) of a run of triangles seen from one point, the inner loop
// of the fast winding numbers (solid/fast_winding.h) where a cluster is opened down to its
// triangles. The triangles are arrays of doubles (structure of arrays), so the compiler
// vectorises the loop over them; the arctangent is Cephes' rational approximation written
// with selects (within 5e-16 of libm's atan2), since libm's does not vectorise. Same formula
// as triangleWinding() (van Oosterom & Strackee); tests/native/test_solid.cpp compares the
// fast winding numbers with cluster expansions off against a sum of triangleWinding().
#include <array>
#include <cstddef>

namespace hyvox::solid {

// corners[3 c + k]: coordinate k of corner c of every triangle.
struct TriangleArrays {
    std::array<const double*, 9> corners;
};

// Σ solid angle / 4π of triangles [first, first + count) seen from q.
double solidAngleSum(const TriangleArrays& triangles, std::size_t first, std::size_t count,
                     const std::array<double, 3>& q);

// The same in float, twice the lanes, for a box's near triangles (solid/box_winding.cpp):
// corners and q relative to a point near them all (the box's centre, so that the coordinates
// are tens of voxels, not thousands), and q at least half a voxel from every triangle (an
// outright voxel's centre: its box meets no triangle). Each term is then within about 1e-6 of
// the double one (tests/native/test_solid.cpp compares them); summed in double.
struct FloatTriangleArrays {
    std::array<const float*, 9> corners;
};
double solidAngleSum(const FloatTriangleArrays& triangles, std::size_t count, const std::array<float, 3>& q);

}  // namespace hyvox::solid
