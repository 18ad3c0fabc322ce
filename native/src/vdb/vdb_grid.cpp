// SPDX-License-Identifier: GPL-3.0-or-later
// All of hyvox's OpenVDB code in one translation unit: OpenVDB headers compile slowly.
#include "vdb/vdb_grid.h"

#include <openvdb/io/Archive.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <memory>
#include <mutex>
#include <ostream>

#include "hyvox/errors.h"
#include "hyvox/region.h"
#include "hyvox/vdb.h"
#include "hyvox/version.h"
#include "os/atomic_file.h"
#include "vdb/vdb_attribute_grids.h"

namespace hyvox::vdb {
namespace {

using FloatLeaf = openvdb::FloatTree::LeafNodeType;
static_assert(FloatLeaf::LOG2DIM == BrickLayout::kLog2, "BitGrid bricks must match OpenVDB leaves");
static_assert(FloatLeaf::NodeMaskType::WORD_COUNT == BitGrid::kWordsPerBrick, "leaf mask is 8 64-bit words");

void addMetadata(openvdb::GridBase& target, const VoxelizeResult& result) {
    target.setCreator(std::string("hyvox ") + version());
    target.insertMeta("hyvox_version", openvdb::StringMetadata(version()));
    target.insertMeta("hyvox_method", openvdb::StringMetadata(result.stats.method));
    target.insertMeta("hyvox_mode", openvdb::StringMetadata(result.stats.mode));
    target.insertMeta("hyvox_voxel_size", openvdb::DoubleMetadata(result.grid.voxel_size));
    const auto& o = result.grid.origin;
    target.insertMeta("hyvox_origin", openvdb::Vec3DMetadata(openvdb::Vec3d(o[0], o[1], o[2])));
    const auto& d = result.grid.dims;
    target.insertMeta("hyvox_dims", openvdb::Vec3IMetadata(openvdb::Vec3i(d[0], d[1], d[2])));
    const RegionOptions& region = result.stats.options.region;
    if (!region.whole()) target.insertMeta("hyvox_region", openvdb::StringMetadata(formatRegion(region)));
}

// io::File::write() opens its own std::ofstream and never checks it after writing, so a full
// disk would go unnoticed. Archive::write() to a stream we own (seekable, exactly what
// File::write does) lets every write error surface.
class CheckedArchive : public openvdb::io::Archive {
public:
    void writeTo(std::ostream& os, const openvdb::GridCPtrVec& grids) const {
        write(os, grids, /*seekable=*/true, openvdb::MetaMap());
    }
};

}  // namespace

void initializeOpenVdb() {
    static std::once_flag once;
    std::call_once(once, [] { openvdb::initialize(); });
}

openvdb::math::Transform::Ptr makeTransform(const GridSpec& grid) {
    checkVdbVoxelSize(grid.voxel_size);
    auto transform = openvdb::math::Transform::createLinearTransform(grid.voxel_size);
    const double h = 0.5 * grid.voxel_size;
    transform->postTranslate(openvdb::Vec3d(grid.origin[0] + h, grid.origin[1] + h, grid.origin[2] + h));
    return transform;
}

namespace {

// An empty fog-volume float grid (background 0) named `name`, on grid's transform.
openvdb::FloatGrid::Ptr makeFogGrid(const char* name, const GridSpec& grid) {
    initializeOpenVdb();
    auto result = openvdb::FloatGrid::create(0.0f);
    result->setName(name);
    result->setGridClass(openvdb::GRID_FOG_VOLUME);
    result->setTransform(makeTransform(grid));
    return result;
}

}  // namespace

openvdb::FloatGrid::Ptr makeDensityGrid(const GridSpec& grid, const SparseGrid& occupancy,
                                        const std::vector<std::uint64_t>& full_leaves) {
    auto result = makeFogGrid("density", grid);
    const BrickLayout& bricks = occupancy.bricks();
    const std::vector<SparseGrid::Leaf>& source = occupancy.leaves();
    // Leaves are built in parallel (most of the work: 512 floats each) and handed to the
    // tree serially (addLeaf is not thread-safe, and cheap).
    std::vector<std::unique_ptr<FloatLeaf>> leaves(source.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, source.size(), 256), [&](const auto& range) {
        for (std::size_t n = range.begin(); n != range.end(); ++n) {
            const SparseGrid::Leaf& from = source[n];
            const std::array<std::int32_t, 3> at = bricks.at(from.brick);
            const int side = BrickLayout::kSide;
            auto leaf =
                std::make_unique<FloatLeaf>(openvdb::Coord(at[0] * side, at[1] * side, at[2] * side), 0.0f, false);
            auto& mask = leaf->getValueMask();
            for (int w = 0; w < BitGrid::kWordsPerBrick; ++w) mask.template getWord<std::uint64_t>(w) = from.words[w];
            float* values = leaf->buffer().data();
            for (int v = 0; v < 512; ++v) values[v] = float((from.words[v >> 6] >> (v & 63)) & 1u);
            leaves[n] = std::move(leaf);
        }
    });
    auto& tree = result->tree();
    for (auto& leaf : leaves) tree.addLeaf(leaf.release());
    // Whole bricks (a solid's interior) are active level-1 tiles, one per 8³ leaf, no leaf
    // allocated; pruning then folds internal nodes that are wholly such tiles into tiles of
    // their own level, so a solid costs memory along its surface only.
    if (!occupancy.tileRuns().empty()) {
        openvdb::FloatGrid::Accessor accessor(tree);
        for (const SparseGrid::TileRun& run : occupancy.tileRuns())
            for (std::uint64_t b = run.begin; b < run.end; ++b) {
                const std::array<std::int32_t, 3> at = bricks.at(b);
                const int side = BrickLayout::kSide;
                if (!std::binary_search(full_leaves.begin(), full_leaves.end(), std::uint64_t(b)))
                    accessor.addTile(1, openvdb::Coord(at[0] * side, at[1] * side, at[2] * side), 1.0f, true);
            }
        tree.prune();
        // After prune(), which would fold these constant leaves back into tiles.
        for (std::uint64_t b : full_leaves) {
            const std::array<std::int32_t, 3> at = bricks.at(b);
            const int side = BrickLayout::kSide;
            accessor.addLeaf(new FloatLeaf(openvdb::Coord(at[0] * side, at[1] * side, at[2] * side), 1.0f, true));
        }
    }
    return result;
}

openvdb::FloatGrid::Ptr makeCountGrid(const GridSpec& grid, const std::vector<VoxelCount>& counts) {
    auto result = makeFogGrid("count", grid);
    auto accessor = result->getAccessor();
    for (const VoxelCount& c : counts) accessor.setValueOn(openvdb::Coord(c.i, c.j, c.k), float(c.count));
    return result;
}

openvdb::FloatGrid::Ptr makeLevelSetGrid(const VoxelizeResult& result) {
    initializeOpenVdb();
    const LevelSetGrid& sdf = result.sdf;
    const float background = sdf.background;
    auto grid = openvdb::FloatGrid::create(background);
    grid->setName("sdf");
    grid->setGridClass(openvdb::GRID_LEVEL_SET);
    grid->setTransform(makeTransform(result.grid));
    const BrickLayout bricks = result.grid.bricks();
    const int side = BrickLayout::kSide;
    std::vector<std::unique_ptr<FloatLeaf>> leaves(sdf.leaves.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, sdf.leaves.size(), 256), [&](const auto& range) {
        for (std::size_t n = range.begin(); n != range.end(); ++n) {
            const LevelSetGrid::Leaf& from = sdf.leaves[n];
            const std::array<std::int32_t, 3> at = bricks.at(from.brick);
            auto leaf = std::make_unique<FloatLeaf>(openvdb::Coord(at[0] * side, at[1] * side, at[2] * side),
                                                    background, false);
            auto& mask = leaf->getValueMask();
            for (int w = 0; w < BitGrid::kWordsPerBrick; ++w) mask.template getWord<std::uint64_t>(w) = from.active[w];
            float* values = leaf->buffer().data();
            std::size_t next = from.first;
            for (int v = 0; v < 512; ++v) {
                const bool active = (from.active[v >> 6] >> (v & 63)) & 1,
                           inside = (from.inside[v >> 6] >> (v & 63)) & 1;
                values[v] = active ? sdf.values[next++] : inside ? -background : background;
            }
            leaves[n] = std::move(leaf);
        }
    });
    auto& tree = grid->tree();
    for (auto& leaf : leaves) tree.addLeaf(leaf.release());
    openvdb::FloatGrid::Accessor accessor(tree);
    for (const SparseGrid::TileRun& run : sdf.inside_runs)
        for (std::uint64_t b = run.begin; b < run.end; ++b) {
            const std::array<std::int32_t, 3> at = bricks.at(b);
            accessor.addTile(1, openvdb::Coord(at[0] * side, at[1] * side, at[2] * side), -background, false);
        }
    tree.prune();  // inside tiles filling a node become the node's tile, as the .vdb writer writes them
    return grid;
}

openvdb::GridPtrVec makeGrids(const VoxelizeResult& result) {
    openvdb::GridPtrVec grids;
    grids.push_back(makeDensityGrid(result.grid, result.occupancy, result.attributes.valued_tile_bricks));
    if (writesCountGrid(result)) grids.push_back(makeCountGrid(result.grid, result.counts));
    for (auto& grid : makeAttributeGrids(result)) grids.push_back(grid);
    if (!result.sdf.empty()) grids.push_back(makeLevelSetGrid(result));
    for (auto& g : grids) addMetadata(*g, result);
    return grids;
}

void writeGridsAtomic(const openvdb::GridCPtrVec& grids, const std::string& path) {
    initializeOpenVdb();
    // The temporary is removed unless the whole write and commit succeed.
    os::AtomicFile(path).writeWith([&](std::ostream& out) {
        try {
            CheckedArchive().writeTo(out, grids);
        } catch (const openvdb::Exception& e) {
            throw ResourceError("writing '" + path + "' failed: " + e.what());
        }
    });
}

}  // namespace hyvox::vdb
