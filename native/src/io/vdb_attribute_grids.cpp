// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/vdb_attribute_grids.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <memory>
#include <vector>

#include "io/vdb_grid.h"

namespace hyvox::io {
namespace {

// The first value (voxel number in coords() order) of every leaf: the running count of set bits.
std::vector<std::size_t> leafStarts(const SparseGrid& occupancy) {
    std::vector<std::size_t> starts;
    starts.reserve(occupancy.leafCount());
    std::size_t total = 0;
    for (const SparseGrid::Leaf& leaf : occupancy.leaves()) {
        starts.push_back(total);
        for (std::uint64_t word : leaf.words) total += std::size_t(__builtin_popcountll(word));
    }
    return starts;
}

// A grid of `width` channels (1: float, 3: Vec3f) taken from the attribute values at
// channel `offset`, one leaf per occupied leaf, built in parallel and added serially.
template <typename GridType>
typename GridType::Ptr makeGrid(const VoxelizeResult& result, const char* name, int offset,
                                const std::vector<std::size_t>& starts) {
    using Leaf = typename GridType::TreeType::LeafNodeType;
    using Value = typename GridType::ValueType;
    initializeOpenVdb();
    auto grid = GridType::create(Value(0));
    grid->setName(name);
    grid->setTransform(makeTransform(result.grid));
    const AttributeGrid& a = result.attributes;
    const std::size_t channels = std::size_t(a.channels());
    const auto& source = result.occupancy.leaves();
    const BrickLayout& bricks = result.occupancy.bricks();
    std::vector<std::unique_ptr<Leaf>> leaves(source.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, source.size(), 256), [&](const auto& range) {
        for (std::size_t n = range.begin(); n != range.end(); ++n) {
            const SparseGrid::Leaf& from = source[n];
            const std::array<std::int32_t, 3> at = bricks.at(from.brick);
            auto leaf = std::make_unique<Leaf>(openvdb::Coord(at[0] * 8, at[1] * 8, at[2] * 8), Value(0), false);
            auto& mask = leaf->getValueMask();
            for (int w = 0; w < BitGrid::kWordsPerBrick; ++w) mask.template getWord<std::uint64_t>(w) = from.words[w];
            Value* values = leaf->buffer().data();
            std::size_t voxel = starts[n];
            for (int v = 0; v < 512; ++v) {
                if (!((from.words[v >> 6] >> (v & 63)) & 1u)) continue;
                const float* value = &a.values[voxel++ * channels + std::size_t(offset)];
                if constexpr (std::is_same_v<Value, float>)
                    values[v] = value[0];
                else
                    values[v] = Value(value[0], value[1], value[2]);
            }
            leaves[n] = std::move(leaf);
        }
    });
    for (auto& leaf : leaves) grid->tree().addLeaf(leaf.release());
    return grid;
}

}  // namespace

openvdb::GridPtrVec makeAttributeGrids(const VoxelizeResult& result) {
    openvdb::GridPtrVec grids;
    const AttributeGrid& a = result.attributes;
    if (a.empty()) return grids;
    const std::vector<std::size_t> starts = leafStarts(result.occupancy);
    if (a.color) {
        auto color = makeGrid<openvdb::Vec3SGrid>(result, "color", a.colorOffset(), starts);
        color->setVectorType(openvdb::VEC_INVARIANT);
        grids.push_back(color);
    }
    if (a.alpha) grids.push_back(makeGrid<openvdb::FloatGrid>(result, "alpha", a.alphaOffset(), starts));
    if (a.normal) {
        auto normal = makeGrid<openvdb::Vec3SGrid>(result, "normal", a.normalOffset(), starts);
        normal->setVectorType(openvdb::VEC_COVARIANT_NORMALIZE);
        grids.push_back(normal);
    }
    return grids;
}

}  // namespace hyvox::io
