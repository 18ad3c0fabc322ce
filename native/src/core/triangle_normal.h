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
// The choice depends only on the corners' values: a rotation of the corners picks the same
// edges and gives the same normal bit for bit, a reflection picks them reversed and gives its
// exact negation (b x a = -(a x b) and -(p - q) = q - p in floating point). A tie for the
// longest edge is broken by the corner opposite it (the lexicographically smaller); tied
// edges whose opposite corners are equal both leave a zero edge, and both give zero.
#include <array>

namespace hyvox {

using Corner3 = std::array<double, 3>;

inline Corner3 stableTriangleNormal(const Corner3& c0, const Corner3& c1, const Corner3& c2) {
    const Corner3* c[3] = {&c0, &c1, &c2};
    Corner3 e[3];
    double length2[3];
    for (int i = 0; i < 3; ++i) {
        const Corner3& from = *c[i];
        const Corner3& to = *c[i == 2 ? 0 : i + 1];
        e[i] = {to[0] - from[0], to[1] - from[1], to[2] - from[2]};
        length2[i] = e[i][0] * e[i][0] + e[i][1] * e[i][1] + e[i][2] * e[i][2];
    }
    // Edge i is opposite corner i + 2.
    int longest = 0;
    for (int i = 1; i < 3; ++i)
        if (length2[i] > length2[longest] ||
            (length2[i] == length2[longest] && *c[(i + 2) % 3] < *c[(longest + 2) % 3]))
            longest = i;
    const Corner3& a = e[(longest + 1) % 3];
    const Corner3& b = e[(longest + 2) % 3];
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

}  // namespace hyvox
