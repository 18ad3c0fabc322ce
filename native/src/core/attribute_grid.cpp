// SPDX-License-Identifier: GPL-3.0-or-later
#include "hyvox/attribute_grid.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace hyvox {
namespace {

std::size_t popcount(const std::uint64_t* mask) {
    std::size_t n = 0;
    for (int w = 0; w < BitGrid::kWordsPerBrick; ++w) n += std::size_t(__builtin_popcountll(mask[w]));
    return n;
}

}  // namespace

std::vector<ValuedBrick> valuedBricks(const SparseGrid& occupancy, const AttributeGrid& attributes) {
    std::vector<ValuedBrick> out;
    out.reserve(occupancy.leafCount() + attributes.valued_tile_bricks.size());
    const auto& leaves = occupancy.leaves();
    const auto& tiles = attributes.valued_tile_bricks;
    std::size_t l = 0, t = 0, first = 0;
    while (l < leaves.size() || t < tiles.size()) {
        const bool leaf = t == tiles.size() || (l < leaves.size() && leaves[l].brick < tiles[t]);
        const ValuedBrick brick = leaf ? ValuedBrick{leaves[l].brick, leaves[l].words, first}
                                       : ValuedBrick{tiles[t], BitGrid::kFullBrick, first};
        leaf ? ++l : ++t;
        first += popcount(brick.mask);
        out.push_back(brick);
    }
    return out;
}

std::vector<float> valuesInCoordsOrder(const SparseGrid& occupancy, const AttributeGrid& attributes) {
    if (attributes.empty()) return {};
    const std::size_t channels = std::size_t(attributes.channels());
    if (attributes.tiles.empty() && attributes.valued_tile_bricks.size() == occupancy.tileCount()) {
        if (attributes.values.size() != occupancy.count() * channels)
            throw std::logic_error("attribute values do not match the occupancy");
        return attributes.values;  // every brick valued voxel by voxel: coords() order already
    }
    // Each tile brick's region, by brick: a region's bricks listed from its box.
    const BrickLayout& bricks = occupancy.bricks();
    std::vector<std::pair<std::uint64_t, std::uint32_t>> region_of;
    for (std::size_t r = 0; r < attributes.tiles.size(); ++r) {
        const AttributeTile& tile = attributes.tiles[r];
        const std::int32_t side = tile.side() / BrickLayout::kSide;
        std::array<std::int32_t, 3> lo{}, hi{};
        for (int a = 0; a < 3; ++a) {
            lo[a] = tile.origin[a] / BrickLayout::kSide;
            hi[a] = std::min(lo[a] + side, bricks.counts[a]);
        }
        for (std::int32_t x = lo[0]; x < hi[0]; ++x)
            for (std::int32_t y = lo[1]; y < hi[1]; ++y)
                for (std::int32_t z = lo[2]; z < hi[2]; ++z)
                    region_of.emplace_back(bricks.index(x, y, z), std::uint32_t(r));
    }
    std::sort(region_of.begin(), region_of.end());
    const std::vector<ValuedBrick> valued = valuedBricks(occupancy, attributes);
    std::vector<float> out;
    out.reserve(occupancy.count() * channels);
    // coords() order: bricks ascending, leaves and tile bricks merged.
    std::size_t v = 0, r = 0;
    auto copyValued = [&](const ValuedBrick& brick) {
        const std::size_t n = popcount(brick.mask) * channels;
        const float* from = attributes.values.data() + brick.first * channels;
        out.insert(out.end(), from, from + n);
    };
    auto tileBrick = [&](std::uint64_t brick) {
        while (v < valued.size() && valued[v].brick < brick) copyValued(valued[v++]);
        if (v < valued.size() && valued[v].brick == brick) {
            copyValued(valued[v++]);
            return;
        }
        while (r < region_of.size() && region_of[r].first < brick) ++r;
        if (r == region_of.size() || region_of[r].first != brick)
            throw std::logic_error("a tile brick has neither values nor a tile region");
        const float* value = attributes.tiles[region_of[r].second].values.data();
        for (int n = 0; n < 512; ++n) out.insert(out.end(), value, value + channels);
    };
    for (const SparseGrid::TileRun& run : occupancy.tileRuns())
        for (std::uint64_t b = run.begin; b < run.end; ++b) tileBrick(b);
    while (v < valued.size()) copyValued(valued[v++]);
    return out;
}

}  // namespace hyvox
