// SPDX-License-Identifier: GPL-3.0-or-later
#include "gl/bit_tiles.h"

#include <algorithm>
#include <string>

#include "core/stopwatch.h"
#include "gl/gl_debug.h"
#include "gl/gl_limits.h"
#include "hyvox/errors.h"

namespace hyvox::gl {
namespace {

// The largest tile in bytes: one storage block, or less when the options ask for it.
std::uint64_t tileByteLimit(std::uint64_t tile_bytes) {
    std::uint64_t limit = std::uint64_t(glLimit(GL_MAX_SHADER_STORAGE_BLOCK_SIZE));
    if (tile_bytes) limit = std::min(limit, tile_bytes);
    // 32-bit word indices in the shaders.
    return std::min<std::uint64_t>(limit, std::uint64_t(1) << 33);
}

}  // namespace

BitTiling::BitTiling(const GridSpec& grid, std::uint64_t tile_bytes) : grid_(grid), bricks_(grid.bricks()) {
    const std::uint64_t slab_bytes = slabBytes();
    const std::uint64_t limit = tileByteLimit(tile_bytes);
    // In bytes: a gl_tile_bytes below one slab (a few KiB on small grids) shows as "0 MiB".
    if (slab_bytes > limit && tile_bytes && tile_bytes == limit)
        throw InvalidInput("gl_tile_bytes " + std::to_string(tile_bytes) + " is less than one 8-voxel slab of this " +
                           grid.dimsText() + " grid (" + std::to_string(slab_bytes) + " bytes); give at least that");
    if (slab_bytes > limit)
        throw ResourceError("a " + grid.dimsText() + " grid needs " + std::to_string(slab_bytes) +
                            " bytes per 8-voxel slab, more than this GL device's storage-block limit of " +
                            std::to_string(limit) + " bytes; use a larger voxel size");
    bricks_per_tile_ = int(std::min<std::uint64_t>(std::uint64_t(bricks_.counts[0]), limit / slab_bytes));
    for (int x0 = 0; x0 < bricks_.counts[0]; x0 += bricks_per_tile_)
        tiles_.push_back({x0, std::min(bricks_.counts[0], x0 + bricks_per_tile_)});
}

std::size_t BitTiling::slabBytes() const {
    return std::size_t(bricks_.counts[1]) * std::size_t(bricks_.counts[2]) * kBrickBytes;
}

std::array<int, 2> BitTiling::voxelSlab(const BitTile& tile) const {
    return {tile.brick_x0 * BrickLayout::kSide, std::min(grid_.dims[0], tile.brick_x1 * BrickLayout::kSide)};
}

double BitTiling::run(const Buffer& bits, BitGrid* out, const std::function<void(const BitTile&)>& work) const {
    double readback_ms = 0;
    for (const BitTile& tile : tiles_) {
        work(tile);
        if (out) readback_ms += readBack(bits, tile, *out);
    }
    return readback_ms;
}

double BitTiling::readBack(const Buffer& bits, const BitTile& tile, BitGrid& out) const {
    Stopwatch watch;
    // Tiles are whole slabs of bricks: contiguous in the leaf layout, copied in place.
    const std::size_t offset = std::size_t(tile.brick_x0) * slabBytes();
    const std::size_t bytes = std::size_t(tile.brick_x1 - tile.brick_x0) * slabBytes();
    bits.download(0, bytes, reinterpret_cast<unsigned char*>(out.data()) + offset);
    checkGl("reading back the bit grid");
    return watch.elapsedMs();
}

}  // namespace hyvox::gl
