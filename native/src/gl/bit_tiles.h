// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The bit grid on the GPU in tiles: slabs of whole 8³ bricks along x. A slab is contiguous in
// the OpenVDB leaf layout (hyvox/bit_grid.h), so each tile reads back straight into place.
// A tile is at most one shader storage block (GL_MAX_SHADER_STORAGE_BLOCK_SIZE), or
// GlOptions::tile_bytes when that is smaller (tests of the tile borders use it). Construct
// and run on the GL worker thread.
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "gl/gl_objects.h"
#include "hyvox/bit_grid.h"
#include "hyvox/grid.h"

namespace hyvox::gl {

struct BitTile {
    int brick_x0 = 0, brick_x1 = 0;  // [x0, x1) in bricks
};

class BitTiling {
public:
    static constexpr std::size_t kBrickBytes = BitGrid::kWordsPerBrick * sizeof(std::uint64_t);

    // Lays out the tiles for `grid`; tile_bytes = GlOptions::tile_bytes (0 = no limit of
    // its own). Throws ResourceError when one slab of bricks alone exceeds the limit.
    BitTiling(const GridSpec& grid, std::uint64_t tile_bytes);

    const std::vector<BitTile>& tiles() const { return tiles_; }
    // The largest tile: what the bit buffer on the GPU must hold.
    std::size_t maxTileBytes() const { return std::size_t(bricks_per_tile_) * slabBytes(); }
    // The voxels [x0, x1) along x a tile covers, clipped to the grid (HYVOX_LOC_SLAB).
    std::array<int, 2> voxelSlab(const BitTile& tile) const;

    // Runs each tile in order: work(tile) leaves that tile's bits in `bits` (from offset 0);
    // unless `out` is null (timing runs) they are then copied into place in *out. Returns the
    // milliseconds the copies took.
    double run(const Buffer& bits, BitGrid* out, const std::function<void(const BitTile&)>& work) const;
    // Copies one tile's bits (any whole slabs of bricks, from offset 0 of `bits`) into place in
    // *out; returns the milliseconds it took.
    double readBack(const Buffer& bits, const BitTile& tile, BitGrid& out) const;

private:
    std::size_t slabBytes() const;  // one slab of bricks: 8 voxels along x

    GridSpec grid_;
    BrickLayout bricks_;
    int bricks_per_tile_ = 1;
    std::vector<BitTile> tiles_;
};

}  // namespace hyvox::gl
