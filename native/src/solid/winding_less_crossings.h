// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// w - c, the winding number at a point less the signed crossings c of the ray from it straight
// down (solid/ray_crossings.h): what an open mesh's smooth winding (solid/smooth_winding.h)
// samples at points on the voxel columns' centre lines. Two ways to it:
//  - the fast winding numbers' tree (solid/fast_winding.h), less c (TreeLessCrossings): a
//    build of n log n over the triangles, then a walk of the tree per point;
//  - the sheets of all the open edges (solid/sheet_winding.h): w - c = -Σ excess · (the
//    sheets' winding numbers), exactly, with no tree: a term per open edge per point.
#include <cstddef>

#include "solid/fast_winding.h"

namespace hyvox::solid {

class WindingLessCrossings {
public:
    virtual ~WindingLessCrossings() = default;
    // w - c at `count` points on voxel columns' centre lines, `below[n]` the signed crossings
    // below point n. `together`: the points lie close together (a brick's, a block's), so that
    // work shared by all of them pays.
    virtual void at(const Vec3* points, const int* below, std::size_t count, bool together, double* out) const = 0;
};

class TreeLessCrossings final : public WindingLessCrossings {
public:
    explicit TreeLessCrossings(const FastWinding& tree) : tree_(tree) {}
    // together: FastWinding::atBox (the clusters far from all the points evaluated once); else
    // FastWinding::atMany (equal to at() bit for bit).
    void at(const Vec3* points, const int* below, std::size_t count, bool together, double* out) const override {
        if (together)
            tree_.atBox(points, count, out);
        else
            tree_.atMany(points, count, out);
        for (std::size_t n = 0; n < count; ++n) out[n] -= below[n];
    }

private:
    const FastWinding& tree_;
};

}  // namespace hyvox::solid
