// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Attribute voxels of the tessellation method (section 3.2's multi-valued voxels): each point
// adds its triangle's attributes at its barycentrics to per-voxel sums beside its count
// (shaders/tessellation/point_values.glsl); a voxel's value is the mean of its points.
// Here: the per-corner values the shaders interpolate, and the means from the read-back sums.
#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/attribute_evaluator.h"
#include "core/attribute_leaf.h"
#include "hyvox/bit_grid.h"
#include "hyvox/grid.h"
#include "hyvox/mesh.h"
#include "hyvox/texture.h"

namespace hyvox::tessellation {

// The sums' fixed point: each point's value is clamped to ±kValueLimit and rounded to a
// multiple of 1 / kValueScale (so it fits 32 bits), then summed exactly in 64 bits. Means
// are thus within 2^-19 of the float ones; colours and normals are far inside the limit.
constexpr double kValueScale = 262144.0;  // 2^18
constexpr double kValueLimit = 8191.0;

struct PointValues {
    AttributeGrid layout;  // the channels (values empty)
    // With a texture the colour slots of `corners` hold the corner's (u, v) and the shaders
    // sample the texture at the interpolated UV; otherwise the values are linear in the
    // barycentrics (vertex/corner colours, palette, normals) and are interpolated directly.
    const Texture* texture = nullptr;
    std::vector<float> corners;  // layout.channels() per corner, 3 corners per usable triangle

    int channels() const { return layout.channels(); }
    // The shader #defines of this layout.
    std::string defines() const;
};

// The corner values of `mesh`'s usable triangles (in usable order, as uploaded to the GPU);
// the geometric normal is taken in voxel space, as the exact methods do.
PointValues makePointValues(const ValidatedMesh& mesh, const GridSpec& grid, const AttributeEvaluator& values);

// Words of the value pool per count block: two per channel per voxel.
inline std::uint64_t valueWordsPerBlock(int channels) { return 512ull * 2ull * std::uint64_t(channels); }

// The largest tile, in bytes of its bits (64 per 8³ brick), whose every brick could take a
// count block and its sums within one storage block (`storage_block` bytes) and `budget`
// bytes: the dispatcher's tile limit with attributes, so the sums never run out of room
// however much of the tile the surface reaches.
inline std::uint64_t tileBitBytesForSums(std::uint64_t storage_block, std::uint64_t budget, int channels) {
    const std::uint64_t value_bytes = valueWordsPerBlock(channels) * 4, count_bytes = 512 * 4;
    const std::uint64_t bricks =
        std::min({storage_block / value_bytes, storage_block / count_bytes, budget / (value_bytes + count_bytes)});
    return std::max<std::uint64_t>(bricks, 1) * 64;
}

// The means of every set voxel of the tile, one leaf per non-empty brick (bit order), from
// the blocks' counts and sums: colours are sum / count, normals the direction of the sum
// (zero when it cancels: attributes::meanOfSums). Returns the set voxels that had no count (given zeros; none expected).
std::uint64_t meansFromSums(const std::vector<std::uint32_t>& brick_blocks,
                            const std::vector<std::uint32_t>& count_pool, const std::vector<std::uint32_t>& value_pool,
                            const BitGrid& bits, const std::array<std::int32_t, 3>& tile_offset, const GridSpec& grid,
                            const AttributeGrid& layout, std::vector<AttributeLeaf>& out);

}  // namespace hyvox::tessellation
