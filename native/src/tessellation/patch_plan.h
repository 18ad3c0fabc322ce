// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Which patches the tessellation draw gets: every usable triangle whose Eq. 1 factors fit
// GL_MAX_TESS_GEN_LEVEL is one patch; the others are split into n² sub-triangles first (the
// vertex shader derives each sub-triangle from its patch number, so no geometry is written).
// Triangles the tessellator would not subdivide at all skip the draw.
#include <array>
#include <cstdint>
#include <vector>

#include "hyvox/grid.h"
#include "hyvox/mesh.h"

namespace hyvox::tessellation {

struct PatchPlan {
    // Usable-triangle indices whose factors are all <= 1: the tessellator would return them
    // whole, so a compute pass injects their one point each without the tessellation draw.
    std::vector<std::uint32_t> whole;
    std::vector<std::uint32_t> direct;  // usable-triangle indices drawn as one patch each
    std::vector<std::uint32_t> splits;  // 4 per split triangle: usable index, n, first patch, 0
    std::uint64_t split_patches = 0;    // Σ n²
    std::uint32_t largest_split = 1;    // largest n
    // An upper estimate of the 8³ bricks the points reach (sizes the per-voxel count pool):
    // the union of the small triangles' bounding boxes in bricks, grown by `reach`, plus an
    // area-based share for triangles spanning many bricks.
    std::uint64_t brick_estimate = 0;
    std::uint64_t points_estimate = 0;  // Σ over triangles of (largest factor)², at least 1 each
};

// The most points one run may make (its GPU counters are 32-bit); planPatches refuses more.
constexpr std::uint64_t kMaxPoints = 0xffffffffull;

// ResourceError when the points would exceed kMaxPoints. `gamma` and `max_level` as in Eq. 1 and GL_MAX_TESS_GEN_LEVEL; the factors come from the
// whole grid's voxel space. With `estimate_bricks`, the bricks are those of the tile being
// filled (voxels tile_offset .. + tile_dims): `reach` = how far (voxels) points may leave
// the flat triangle (displacement), `pn_reach` the same as a share of each triangle's
// largest extent (PN bulge).
PatchPlan planPatches(const ValidatedMesh& mesh, const GridSpec& grid, const std::array<std::int32_t, 3>& tile_offset,
                      const std::array<std::int32_t, 3>& tile_dims, double gamma, int max_level, bool estimate_bricks,
                      double reach, double pn_reach);

}  // namespace hyvox::tessellation
