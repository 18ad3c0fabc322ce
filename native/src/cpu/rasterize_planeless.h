// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Triangles without a plane in voxel space: the cross product of their two shortest
// voxel-space edges (core/triangle_normal.h) is exactly zero in double. validate() has
// already skipped the triangles of zero area in world space; these have an area that voxel
// space cannot hold. A needle with two corners 1e-37
// apart beside a third at 1e33 becomes, once the grid's origin and voxel size are applied, a
// segment whose two near ends coincide. What is left (a segment, or a point) still touches
// voxels, and the rule is the reference's (reference_overlap.h), taken without the plane:
//   conservative: the segment meets the voxel's closed box. Its separating axes are the
//     box's three (the candidate range) and, in each coordinate plane, the normal of the
//     projected segment: each projected edge's line with the voxel's square on it, both
//     sides (the edge tests of both windings);
//   thin: the same with each plane's inscribed diamond in place of the square.
// The candidates are walked slab by slab along the segment's longest axis, so a needle
// across the grid costs its length, not its bounding box.
#include <array>

#include "cpu/mark_voxels.h"
#include "hyvox/options.h"

namespace hyvox::cpu {

// Marks the voxels in lo..hi (inclusive, unswizzled) that the planeless triangle with
// voxel-space corners c touches by the rule above.
void rasterizePlaneless(const std::array<std::array<double, 3>, 3>& c, Mode mode, const std::array<int, 3>& lo,
                        const std::array<int, 3>& hi, WordMarker& marker);

}  // namespace hyvox::cpu
