// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// How the dispatcher cuts the grid, or the box of its region (hyvox/region.h), into tiles:
// brick-aligned cubes sized by the tile_size option or the memory budget, and which
// triangles may reach each.
#include <cstdint>
#include <vector>

#include "core/backends.h"
#include "hyvox/grid.h"
#include "hyvox/mesh.h"
#include "hyvox/options.h"

namespace hyvox::tiling {

struct TilePlan {
    std::array<std::int32_t, 3> side{0, 0, 0};    // voxels per tile along each axis (multiples of 8)
    std::array<std::int32_t, 3> counts{1, 1, 1};  // tiles per axis
    // The voxels the tiles cover, [lo, hi): the whole grid, or its region's box (lo a
    // multiple of 8), whose tiles start at lo.
    std::array<std::int32_t, 3> lo{0, 0, 0}, hi{0, 0, 0};
    bool region = false;  // the box is a region's, not the whole grid
    std::array<std::int32_t, 3> boxDims() const { return {hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]}; }
    // One tile over the whole grid (every triangle reaches it).
    bool whole() const { return !region && counts[0] * counts[1] * counts[2] == 1; }
    std::size_t total() const { return std::size_t(counts[0]) * std::size_t(counts[1]) * std::size_t(counts[2]); }
    Tile tile(std::size_t index) const;
    std::uint64_t tileBytes() const;  // the dense bits of one tile
};

// Over the box of options.region (the whole grid by default). tile_size > 0: cubes of that
// side (rounded up to a multiple of 8). 0: the whole box when its bits fit a quarter of the
// memory budget (at most 256 MiB) and `device_limit` (bytes; 0 = none: the device's largest
// storage buffer, for methods that hold a tile in one), else the largest cubes that do.
TilePlan planTiles(const GridSpec& grid, const VoxelizeOptions& options, std::uint64_t device_limit = 0);

// How far (voxels) a triangle's points may lie outside its bounding box: 0 for every method
// but the tessellation's PN-triangles (a share of the triangle's largest extent) and
// displacement (the largest height offset times the strength), bounded from above.
struct PointReach {
    double fixed = 0;     // voxels
    double relative = 0;  // times the triangle's largest extent, in voxels
};
PointReach pointReach(const GridSpec& grid, const VoxelizeOptions& options);

// For each tile, the usable triangles whose closed voxel range, grown by their reach, meets
// it (the candidates of the conservative test: voxel i meets [lo, hi] iff lo - 1 <= i <= hi),
// ascending. Triangles that reach no tile (outside a region's box) are in none.
// `interrupter` (may be null) is asked every kInterruptCheckTriangles triangles.
std::vector<std::vector<std::uint32_t>> binTriangles(const ValidatedMesh& mesh, const GridSpec& grid,
                                                     const TilePlan& plan, const PointReach& reach,
                                                     Interrupter* interrupter = nullptr);

}  // namespace hyvox::tiling
