// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file
/// Regions of one grid, for render farms: the grid a one-machine run would lay out (same
/// origin, voxel size and dims) cut into N boxes along its longest side at whole 8³ leaves, so
/// that no two boxes share a leaf. A run with the region option voxelizes one box of that
/// grid and writes it as its own .vdb with the grid's transform; `hyvox merge`
/// (hyvox/vdb_merge.h) joins the N files into the one-machine file, voxel for voxel.
#include <array>
#include <cstdint>
#include <string>

#include "hyvox/grid.h"
#include "hyvox/options.h"

namespace hyvox {

/// The most regions a grid can have: one leaf each along the longest side kMaxResolution allows.
constexpr int kMaxRegions = kMaxResolution / BrickLayout::kSide;

/// The voxels [lo, hi) (hi exclusive) of one region: along `axis` (the longest side, the first
/// of equal ones) the leaves floor(K·B/N) .. floor((K+1)·B/N) - 1 of the B leaves along it (the
/// last cut by the grid's end), every voxel of the other two axes.
struct RegionBox {
    int axis = 0;                                 ///< the axis the grid is cut along: 0 x, 1 y, 2 z
    std::array<std::int32_t, 3> lo{0, 0, 0};      ///< the box's first voxel
    std::array<std::int32_t, 3> hi{0, 0, 0};      ///< one past its last voxel
    std::array<std::int32_t, 3> brickLo() const;  ///< the box's first brick: lo / 8
    std::array<std::int32_t, 3> brickHi() const;  ///< one past its last brick: ceil(hi / 8)
};

/// The box of `region` in `grid`.
/// @param grid the whole grid, as the one-machine run lays it out (makeGrid)
/// @param region the box and the number of boxes; count 1 gives the whole grid
/// @throws InvalidInput when the grid has fewer leaves than regions along its longest side
///         (a region would hold no voxel)
RegionBox regionBox(const GridSpec& grid, const RegionOptions& region);

/// The schema's text of a region: "K/N", or "" for the whole grid.
std::string formatRegion(const RegionOptions& region);
/// The region a schema text names.
/// @param text "K/N" (whole numbers, 0 <= K < N <= kMaxRegions) or "" (the whole grid, as
///        "0/1" is)
/// @throws InvalidInput (the schema's message) for any other text
RegionOptions parseRegion(const std::string& text);
/// Whether parseRegion() takes `text`.
bool isRegionText(const std::string& text);

}  // namespace hyvox
