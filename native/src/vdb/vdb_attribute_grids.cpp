// SPDX-License-Identifier: GPL-3.0-or-later
#include "vdb/vdb_attribute_grids.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <memory>
#include <vector>

#include "vdb/vdb_grid.h"

namespace hyvox::vdb {
namespace {

// A grid of `width` channels (1: float, 3: Vec3f) taken from the attribute values at
// channel `offset`: a leaf per valued brick (built in parallel, added serially) and a tile per
// tile region.
template <typename GridType>
typename GridType::Ptr makeGrid(const VoxelizeResult& result, const char* name, int offset,
                                const std::vector<ValuedBrick>& valued) {
    using Leaf = typename GridType::TreeType::LeafNodeType;
    using Value = typename GridType::ValueType;
    initializeOpenVdb();
    auto grid = GridType::create(Value(0));
    grid->setName(name);
    grid->setTransform(makeTransform(result.grid));
    const AttributeGrid& a = result.attributes;
    const std::size_t channels = std::size_t(a.channels());
    const BrickLayout& bricks = result.occupancy.bricks();
    auto valueAt = [](const float* value) {
        if constexpr (std::is_same_v<Value, float>)
            return value[0];
        else
            return Value(value[0], value[1], value[2]);
    };
    std::vector<std::unique_ptr<Leaf>> leaves(valued.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, valued.size(), 256), [&](const auto& range) {
        for (std::size_t n = range.begin(); n != range.end(); ++n) {
            const ValuedBrick& from = valued[n];
            const std::array<std::int32_t, 3> at = bricks.at(from.brick);
            auto leaf = std::make_unique<Leaf>(openvdb::Coord(at[0] * 8, at[1] * 8, at[2] * 8), Value(0), false);
            auto& mask = leaf->getValueMask();
            for (int w = 0; w < BitGrid::kWordsPerBrick; ++w) mask.template getWord<std::uint64_t>(w) = from.mask[w];
            Value* values = leaf->buffer().data();
            std::size_t voxel = from.first;
            for (int v = 0; v < 512; ++v) {
                if (!((from.mask[v >> 6] >> (v & 63)) & 1u)) continue;
                values[v] = valueAt(&a.values[voxel++ * channels + std::size_t(offset)]);
            }
            leaves[n] = std::move(leaf);
        }
    });
    for (auto& leaf : leaves) grid->tree().addLeaf(leaf.release());
    if (!a.tiles.empty()) {
        typename GridType::Accessor accessor(grid->tree());
        for (const AttributeTile& tile : a.tiles)
            accessor.addTile(unsigned(tile.level), openvdb::Coord(tile.origin[0], tile.origin[1], tile.origin[2]),
                             valueAt(tile.values.data() + offset), true);
    }
    return grid;
}

}  // namespace

openvdb::GridPtrVec makeAttributeGrids(const VoxelizeResult& result) {
    openvdb::GridPtrVec grids;
    const AttributeGrid& a = result.attributes;
    if (a.empty()) return grids;
    const std::vector<ValuedBrick> starts = valuedBricks(result.occupancy, a);
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

}  // namespace hyvox::vdb
