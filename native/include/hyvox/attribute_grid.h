// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file
/// Attribute voxels (docs/design.md, "Attributes"): for each occupied voxel, the area-weighted mean
/// of the surface's colour and normal inside its closed box. Values are held per occupied
/// voxel in the order of SparseGrid::coords() (leaf by leaf in brick order, the set bits of a
/// leaf in ascending order), so they stay as sparse as the voxels. A solid's interior tiles
/// hold one value per tile region instead (AttributeGrid::tiles), never one per voxel.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "hyvox/sparse_grid.h"

namespace hyvox {

/// A region of a solid's interior that OpenVDB holds as one active tile (a level-1 tile is one
/// 8³ brick, level 2 a 128³ node, level 3 a 4096³ node: as Tree::prune() merges the density's
/// tiles), holding one attribute value (src/attributes/inside_values.h defines it).
struct AttributeTile {
    std::array<std::int32_t, 3> origin{0, 0, 0};  ///< first voxel, a multiple of the region's side
    int level = 1;                                ///< 1, 2 or 3 (side() voxels a side)
    std::array<float, 7> values{};                ///< channels() used
    /// Voxels along a side of the region.
    std::int32_t side() const { return level == 1 ? 8 : level == 2 ? 128 : 4096; }
};

/// The attribute voxels of a result: which channels, and their values.
struct AttributeGrid {
    bool color = false;   ///< channels 0..2: linear RGB
    bool alpha = false;   ///< then alpha (when the colour source has it)
    bool normal = false;  ///< then a unit normal (zero where the normals cancel)
    /// channels() per valued voxel: the set voxels of the occupancy's leaves and all 512 voxels
    /// of each brick in `valued_tile_bricks`, brick by brick in brick order, each brick's voxels
    /// in ascending bit order. Without `tiles` (every surface mode) this is coords() order.
    std::vector<float> values;
    /// Bricks the occupancy holds as whole tiles whose voxels still have values one by one (they
    /// hold surface voxels, which keep their own values); sorted. The .vdb writes them as full
    /// leaves in every grid, density included, so all grids share one tree shape.
    std::vector<std::uint64_t> valued_tile_bricks;
    /// Solid mode: the occupancy's other tile bricks, one value per region (none in surface modes).
    std::vector<AttributeTile> tiles;

    /// Floats per valued voxel.
    int channels() const { return (color ? 3 : 0) + (alpha ? 1 : 0) + (normal ? 3 : 0); }
    /// No attribute computed.
    bool empty() const { return channels() == 0; }
    /// Voxels with values of their own (tile regions apart).
    std::size_t valuedVoxelCount() const { return empty() ? 0 : values.size() / std::size_t(channels()); }
    int colorOffset() const { return 0; }              ///< the first colour channel in a voxel's values
    int alphaOffset() const { return color ? 3 : 0; }  ///< the alpha channel's place
    int normalOffset() const { return (color ? 3 : 0) + (alpha ? 1 : 0); }  ///< the first normal channel
};

/// One brick whose voxels have values one by one: an occupancy leaf or a valued tile brick
/// (mask all set), with the index in AttributeGrid::values of its first voxel's value.
struct ValuedBrick {
    std::uint64_t brick;        ///< BrickLayout index of the grid
    const std::uint64_t* mask;  ///< 8 words, the occupancy's layout
    std::size_t first;          ///< voxel number (multiply by channels())
};
/// The valued bricks of `attributes` on `occupancy` (finished), in brick order.
std::vector<ValuedBrick> valuedBricks(const SparseGrid& occupancy, const AttributeGrid& attributes);

/// channels() values per voxel in SparseGrid::coords() order (tile voxels included: a tile
/// region's voxels each repeat its value), the layout of the Python arrays.
std::vector<float> valuesInCoordsOrder(const SparseGrid& occupancy, const AttributeGrid& attributes);

}  // namespace hyvox
