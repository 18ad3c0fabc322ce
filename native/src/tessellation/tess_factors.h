// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The adaptive tessellation factors of Eq. 1 (point-tessellated voxelization, section 3.1),
// written once for the CPU so tests, the pre-split planner and the shaders agree on them.
// Points are in voxel space, so "extent / voxel size" is just the extent.
#include <array>

namespace hyvox::tessellation {

using Vec3f = std::array<float, 3>;

// E_ij = γ · |P_i - P_j| (the edge's Euclidean length in voxels): enough segments that every
// segment of the edge is at most 1/γ voxel long (docs/why/tessellation-gamma.md).
double edgeFactor(const Vec3f& a, const Vec3f& b, double gamma);

// GL's order for triangle patches: outer[0] is the edge opposite corner 0 (corners 1-2),
// outer[1] opposite corner 1 (2-0), outer[2] opposite corner 2 (0-1); inner = their mean.
struct PatchFactors {
    std::array<double, 3> outer{};
    double inner = 0;
    double largest() const;
};
PatchFactors patchFactors(const Vec3f& p0, const Vec3f& p1, const Vec3f& p2, double gamma);

// Pieces per edge (n, giving n² sub-triangles) a triangle is split into before tessellation
// so that every sub-edge's factor fits the hardware's GL_MAX_TESS_GEN_LEVEL. 1 = no split.
// This replaces the paper's multi-pass subdivision (Eq. 4-5): one split level always
// suffices because the split count is computed per triangle, not estimated per mesh.
int presplitPieces(const PatchFactors& factors, int max_level);

}  // namespace hyvox::tessellation
