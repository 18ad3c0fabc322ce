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
// normal turned by 1.7e-6 rad and the plane test set the voxels on the wrong side of a
// diagonal the sliver passes 1.5e-5 voxel from. From its two short edges the normal is exact.
//
// The choice depends only on the corners' values, and so does the order the cpu method sets
// a triangle up in (canonicalCornerOrder): the corner opposite the longest edge first, then
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
// from their own cross product, shaders/common/overlap.glsl). Any other triangle keeps its
// plane and windings however thin, in thin mode too: its plane, not its thinness, decides
// which voxel of a column holds it, as for any triangle. A "nearly planeless" tolerance
// would depend on the scale; an exact zero of a computation fixed by the corners' values
// does not, and gives every corner order the same answer.
#include <array>

namespace hyvox {

using Corner3 = std::array<double, 3>;

namespace triangle_normal_detail {

// Lexicographic a < b, without branches (the common case decides on x alone, at random).
inline bool lexLess(const Corner3& a, const Corner3& b) {
    return (a[0] < b[0]) | ((a[0] == b[0]) & ((a[1] < b[1]) | ((a[1] == b[1]) & (a[2] < b[2]))));
}

// The edges e[i] = c[i + 1] - c[i] (edge i is opposite corner i + 2) and the longest's index.
struct Edges {
    Corner3 e[3];
    int longest;
};

inline Edges edgesOf(const Corner3& c0, const Corner3& c1, const Corner3& c2) {
    const Corner3* c[3] = {&c0, &c1, &c2};
    Edges out;
    double length2[3];
    for (int i = 0; i < 3; ++i) {
        const Corner3& from = *c[i];
        const Corner3& to = *c[i == 2 ? 0 : i + 1];
        out.e[i] = {to[0] - from[0], to[1] - from[1], to[2] - from[2]};
        length2[i] = out.e[i][0] * out.e[i][0] + out.e[i][1] * out.e[i][1] + out.e[i][2] * out.e[i][2];
    }
    const bool one_over_zero = length2[1] > length2[0];
    out.longest = length2[2] > (one_over_zero ? length2[1] : length2[0]) ? 2 : int(one_over_zero);
    if (__builtin_expect(length2[0] == length2[1] || length2[1] == length2[2] || length2[2] == length2[0], 0)) {
        // Ties: the edge opposite the lexicographically smaller corner.
        for (int i = 0; i < 3; ++i) {
            const int k = out.longest;
            if (i != k && length2[i] == length2[k] && lexLess(*c[(i + 2) % 3], *c[(k + 2) % 3])) out.longest = i;
        }
    }
    return out;
}

inline Corner3 cross(const Corner3& a, const Corner3& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

}  // namespace triangle_normal_detail

// The corners' indices in canonical order, and whether that order is a reflection of (0, 1, 2).
struct CornerOrder {
    std::array<int, 3> index;
    bool reflected;
};

inline CornerOrder canonicalCornerOrder(const Corner3& c0, const Corner3& c1, const Corner3& c2) {
    const Corner3* c[3] = {&c0, &c1, &c2};
    const int longest = triangle_normal_detail::edgesOf(c0, c1, c2).longest;
    // (opposite, next, last) is a rotation of (0, 1, 2).
    const int opposite = longest == 0 ? 2 : longest - 1, next = longest, last = longest == 2 ? 0 : longest + 1;
    const bool reflected = triangle_normal_detail::lexLess(*c[last], *c[next]);
    return {{opposite, reflected ? last : next, reflected ? next : last}, reflected};
}

// The normal of corners already in canonical order: (p - v) x (q - v), the two shortest edges.
inline Corner3 canonicalNormal(const Corner3& v, const Corner3& p, const Corner3& q) {
    return triangle_normal_detail::cross({p[0] - v[0], p[1] - v[1], p[2] - v[2]},
                                         {q[0] - v[0], q[1] - v[1], q[2] - v[2]});
}

// The normal from the two shortest edges, oriented as c0, c1, c2 wind: e[k+1] x e[k+2] for
// the longest edge k. With (v, p, q) the rotation of the corners that starts opposite edge k,
// e[k+1] = v - q and e[k+2] = p - v, so this is (p - v) x (q - v) bit for bit: the
// canonical corners' canonicalNormal, negated when their order is a reflection.
inline Corner3 stableTriangleNormal(const Corner3& c0, const Corner3& c1, const Corner3& c2) {
    const triangle_normal_detail::Edges edges = triangle_normal_detail::edgesOf(c0, c1, c2);
    const int k = edges.longest;
    return triangle_normal_detail::cross(edges.e[k == 2 ? 0 : k + 1], edges.e[k == 0 ? 2 : k - 1]);
}

}  // namespace hyvox
