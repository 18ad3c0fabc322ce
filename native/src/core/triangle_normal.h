// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A triangle's normal (its doubled area vector) in double, computed so that slivers keep
// their plane and so that the answer does not depend on which corner comes first.
//
// In exact arithmetic e0 x e1 = e1 x e2 = e2 x e0 (e_i = c[i+1] - c[i]); in double they
// differ. Each product term errs by about eps * |a| * |b| (and each edge's own rounding
// adds eps * |edge| per factor), while the true normal is |a| * |b| * sin(angle between
// them), so the pair of edges with the smallest |a| * |b| for the same normal is the most
// accurate: the two shortest, which meet at the corner opposite the longest edge (its angle
// is the largest, at least 60 degrees). A fuzzed sliver 42 voxels long and 2.5e-76 wide
// (tests/fuzz/seeds/voxelize/sliver_beside_a_diagonal.bin) lost its width to e0 x e1: the
// normal turned by 1.7e-6 rad and the plane test set the voxels on the wrong side of a diagonal
// the sliver passes 1.5e-5 voxel from. From its two short edges the normal is exact.
//
// The choice depends only on the corners' values, and so does the order the cpu method sets a
// triangle up in (canonicalCornerOrder): the corner opposite the longest edge first, then
// the other two in lexicographic order. A tie for the longest edge is broken by the corner
// opposite it (the lexicographically smaller); tied edges whose opposite corners are equal
// both leave a zero edge, and both give a zero normal. Any rotation or reflection of the
// corners thus gives the same canonical corners, the same normal bit for bit (negated when
// the canonical order is a reflection of the given one, to keep the given winding), and in
// the cpu method the same voxels.
//
// Planeless means this normal is exactly zero; no tolerance. validate() skips a triangle that
// is planeless in world space (zero area). One that is planeless only in voxel space (its
// width rounded away by the grid) is voxelized as the segment or point it is there
// (cpu/rasterize_planeless.h, and alike in the reference; the GL shaders decide it in float
// from their own cross product, shaders/common/overlap.glsl). Any other
// triangle keeps its plane and windings however thin, in thin mode too: its plane, not its
// thinness, decides which voxel of a column holds it, as for any triangle. A "nearly
// planeless" tolerance would depend on the scale; an exact zero of a computation fixed by
// the corners' values does not, and gives every corner order the same answer.
#include <array>

namespace hyvox {

using Corner3 = std::array<double, 3>;

// The corners' indices in canonical order, and whether that order is a reflection of (0, 1, 2).
struct CornerOrder {
    std::array<int, 3> index;
    bool reflected;
};

inline CornerOrder canonicalCornerOrder(const Corner3& c0, const Corner3& c1, const Corner3& c2) {
    const Corner3* c[3] = {&c0, &c1, &c2};
    double length2[3];  // edge i runs from corner i to corner i + 1, opposite corner i + 2
    for (int i = 0; i < 3; ++i) {
        const Corner3& from = *c[i];
        const Corner3& to = *c[i == 2 ? 0 : i + 1];
        const double d[3] = {to[0] - from[0], to[1] - from[1], to[2] - from[2]};
        length2[i] = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    }
    int longest = 0;
    for (int i = 1; i < 3; ++i)
        if (length2[i] > length2[longest] ||
            (length2[i] == length2[longest] && *c[(i + 2) % 3] < *c[(longest + 2) % 3]))
            longest = i;
    const int first = (longest + 2) % 3, next = longest, last = (longest + 1) % 3;  // (first, next, last) is a rotation
    if (*c[last] < *c[next]) return {{first, last, next}, true};
    return {{first, next, last}, false};
}

// The normal of corners already in canonical order: (p - v) x (q - v), the two shortest edges.
inline Corner3 canonicalNormal(const Corner3& v, const Corner3& p, const Corner3& q) {
    const double a[3] = {p[0] - v[0], p[1] - v[1], p[2] - v[2]};
    const double b[3] = {q[0] - v[0], q[1] - v[1], q[2] - v[2]};
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

// The normal from the two shortest edges, oriented as c0, c1, c2 wind.
inline Corner3 stableTriangleNormal(const Corner3& c0, const Corner3& c1, const Corner3& c2) {
    const Corner3* c[3] = {&c0, &c1, &c2};
    const CornerOrder order = canonicalCornerOrder(c0, c1, c2);
    const Corner3 n = canonicalNormal(*c[order.index[0]], *c[order.index[1]], *c[order.index[2]]);
    return order.reflected ? Corner3{-n[0], -n[1], -n[2]} : n;
}

}  // namespace hyvox
