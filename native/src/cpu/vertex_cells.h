// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A first look at a triangle from integers alone. Each vertex's voxel-space position is
// reduced once to the voxels whose closed boxes hold it along each axis (one voxel, or two
// when it lies on a voxel plane). A triangle's candidate range per axis is then the min /
// max over its corners: the same range setupTriangle derives from the corners' min / max
// coordinates (ceil(clamp(min)) - 1 .. floor(clamp(max))), because clampCoord, ceil and floor
// are monotone. Most triangles of a fine mesh lie within one voxel's range along two axes
// and are decided here (SetupKind::AllCandidates) without any floating-point setup.
#include <algorithm>
#include <array>
#include <cstdint>

#include "core/clamp_coord.h"
#include "cpu/triangle_setup.h"

namespace hyvox::cpu {

struct VertexCell {
    std::int32_t first[3];   // per axis: ceil(x) - 1, the lowest voxel whose closed box holds x
    std::uint32_t on_plane;  // bit a: x[a] is a whole number, so voxel first[a] + 1 holds it too
};

inline VertexCell vertexCell(const std::array<double, 3>& voxel) {
    VertexCell cell{};
    for (int a = 0; a < 3; ++a) {
        const double x = clampCoord(voxel[a]);
        cell.first[a] = ceilToInt(x) - 1;
        cell.on_plane |= std::uint32_t(floorToInt(x) - cell.first[a]) << a;
    }
    return cell;
}

// The triangle's candidate range (triangle_setup.h), from its corners' cells.
inline CandidateRange cellRange(const VertexCell& a, const VertexCell& b, const VertexCell& c,
                                const std::array<std::int32_t, 3>& clip_lo,
                                const std::array<std::int32_t, 3>& clip_hi) {
    CandidateRange r;
    for (int axis = 0; axis < 3; ++axis) {
        const int first = std::min(std::min(a.first[axis], b.first[axis]), c.first[axis]);
        const int last = std::max(
            std::max(a.first[axis] + int(a.on_plane >> axis & 1u), b.first[axis] + int(b.on_plane >> axis & 1u)),
            c.first[axis] + int(c.on_plane >> axis & 1u));
        r.lo[axis] = std::max(clip_lo[axis], first);
        r.hi[axis] = std::min(clip_hi[axis], last);
        r.single[axis] = first == last;
    }
    return r;
}

}  // namespace hyvox::cpu
