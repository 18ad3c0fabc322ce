// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// .vdb files serialized straight from 8³ leaf masks and values, without building an OpenVDB
// tree (and without OpenVDB): OpenVDB reads them back as exactly the grids OpenVDB itself
// would write — same trees, tiles, values, transforms and metadata (test_io_vdb_direct
// compares them).
//
// Why: building a tree allocates 2 KiB of floats per leaf, and OpenVDB's writer then walks,
// copies and compresses them one leaf at a time; here each leaf's bytes are a mask copy and
// its active values, compressed in parallel. Programs that write only through this file (the
// CLI) also never load libopenvdb, whose start-up costs more than a small voxelization.
//
// Format: OpenVDB file version 224 (library 10.0), trees of type Tree_float_5_4_3 or
// Tree_vec3s_5_4_3, background 0 (a level set's: its band), compressed as OpenVDB 10 does by default (COMPRESS_BLOSC |
// COMPRESS_ACTIVE_MASK): every node stores its mask and only its active values, as one
// blosc block made with OpenVDB's settings (libblosc, which OpenVDB itself links), so the
// files are the size of OpenVDB's own and every OpenVDB reader (Blender's included) reads
// them. Not written: OpenVDB's optional "file_delayed_load" metadata (readers do without it).
//
// Grid coordinates are >= 0 (hyvox grids start at voxel 0).
#include <array>
#include <cstddef>
#include <cstdint>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "hyvox/interrupter.h"
#include "hyvox/result.h"

namespace hyvox::vdb {

enum class VdbValueType { Float, Vec3f };  // FloatGrid, Vec3SGrid

// Where a grid's leaves find their active voxels' values (VdbLeaf::values).
enum class VdbLeafValues {
    Fill,    // none: every active voxel holds VdbGrid::fill (density)
    Dense,   // all 512 voxels in OpenVDB's order (x * 64 + y * 8 + z), `stride` floats apart
    Packed,  // the active voxels only, in mask order (word by word, bit by bit), `stride` floats
             // apart: the layout of per-voxel arrays in SparseGrid::coords() order
};

// One leaf: its first voxel (multiples of 8), its 512-bit value mask (OpenVDB's NodeMask<3>
// words: word x, bit y * 8 + z) and where its values start (see VdbLeafValues; ignored
// for Fill). Inactive voxels hold the background, or (a level set's, VdbGrid::background
// not 0) -background where `inside` has their bit.
struct VdbLeaf {
    std::array<std::int32_t, 3> origin;
    const std::uint64_t* mask;
    const float* values = nullptr;
    const std::uint64_t* inside = nullptr;  // level sets: the inactive voxels inside; null = none
};

// An active tile: a whole node's region holding one value (OpenVDB's tile at `level`):
// 1 = an 8³ leaf's region (a tile of a lower internal node), 2 = 128³ (of an upper node),
// 3 = 4096³ (of the root). `origin` is a multiple of the region's side.
struct VdbTile {
    std::array<std::int32_t, 3> origin;
    int level = 1;
    std::array<float, 3> value{1.0f, 1.0f, 1.0f};  // value[0] alone for a Float grid
    bool active = true;                            // false: a level set's inside, holding -background (`value` unused)
};

// One grid of the file. Leaves and tiles may come in any order and must not overlap. Tiles
// are written as Tree::prune() leaves them: active tiles of one value filling a whole node
// become one tile of the level above (so 4096 level-1 tiles in one 128³ node are written as a
// level-2 tile); leaves are written as given.
struct VdbGrid {
    std::string name;
    VdbValueType type = VdbValueType::Float;
    std::string grid_class = "fog volume";  // the "class" metadata; "" = none (OpenVDB: unknown)
    std::string vector_type;                // Vec3f: "invariant", "covariant", "covariant normalize", ...; "" = none
    VdbLeafValues layout = VdbLeafValues::Fill;
    std::array<float, 3> fill{1.0f, 1.0f, 1.0f};  // Fill's value
    // The tree's background (Float grids). A level set's is its band's half-width, and its
    // inactive voxels and tiles hold +background outside and -background inside; 0 otherwise.
    float background = 0.0f;
    std::size_t stride = 0;       // floats between voxels; 0 = channels()
    std::vector<VdbLeaf> leaves;  // they and their values must outlive writeVdbGrids()
    std::vector<VdbTile> tiles;

    int channels() const { return type == VdbValueType::Float ? 1 : 3; }
};

// The leaves whose buffers writeVdbGrids compresses side by side before writing them.
inline constexpr std::size_t kVdbLeavesPerBatch = 4096;

// Writes the file holding `grids` in order to `out`, from its start (`out` must be seekable:
// each grid's positions of its buffers and of its end are written in place once known), each
// grid with the hyvox_* metadata of `result` and its grid transform. Leaf buffers are
// compressed in parallel a batch at a time and written as each batch is done, and the topology
// goes out as it is made, so the write holds one batch's bytes, never the file's.
// `interrupter` (may be null) is asked between batches, with progress from `progress_from` to
// `progress_to`. `threads`: 0 = all cores. Returns the grids' Grid::memUsage() summed (see
// vdbTreeMemUsage). Throws InvalidInput for a leaf or tile off its lattice, below 0, or
// overlapping another.
std::uint64_t writeVdbGrids(std::ostream& out, const VoxelizeResult& result, const std::vector<VdbGrid>& grids,
                            int threads, Interrupter* interrupter = nullptr, int progress_from = 0,
                            int progress_to = 0);

// writeVdbGrids to `path` atomically (os/atomic_file.h; durable: synced): a large file's
// write can be followed and cancelled (hyvox::Cancelled; the temporary is removed, an earlier
// file stays). Returns the grids' memory use.
std::uint64_t writeVdbFile(const std::string& path, const VoxelizeResult& result, const std::vector<VdbGrid>& grids,
                           int threads, bool durable, Interrupter* interrupter, int progress_from, int progress_to);

// Transform::write of the grid's transform (uniform scale voxel_size, translation to the first
// voxel's centre, as createLinearTransform + postTranslate make it): the bytes every grid of
// the file holds.
std::string vdbTransformBytes(const GridSpec& grid);

// OpenVDB's Grid::memUsage() of the tree `grid` makes (its "file_mem_bytes" metadata).
std::uint64_t vdbTreeMemUsage(const VdbGrid& grid);

// ---- Grids of hyvox data ----

// "density": the occupancy's own masks, 1.0 where set; its whole-leaf tiles too, where the
// grid type has them (tileRuns(): runs of brick indices [begin, end), all 512 voxels set),
// as level-1 tiles of 1.0. A template so it also takes a test's stand-in for SparseGrid.
template <typename Occupancy>
VdbGrid densityGrid(const Occupancy& occupancy);

// "density" of a result: densityGrid(result.occupancy), with the tile bricks the attribute
// grids hold voxel by voxel (result.attributes.valued_tile_bricks) as full leaves, so that
// every grid of the file has one tree shape.
VdbGrid resultDensityGrid(const VoxelizeResult& result);

// One attribute as a grid active exactly on the occupancy's voxels: leaves where the values are
// per voxel (valuedBricks), tiles of one value over the solid's tile regions. This grid's
// channels (1 or 3 by `type`) start at channel `offset` of `attributes`. Class none, like
// OpenVDB's default; `vector_type` for Vec3f (see VdbGrid).
VdbGrid attributeGrid(const SparseGrid& occupancy, const AttributeGrid& attributes, int offset, std::string name,
                      VdbValueType type, std::string vector_type = "");

// The attribute voxels' grids (result.attributes), as makeGrids builds them with OpenVDB:
// "color" (Vec3f, vector type invariant: a colour, which Blender reads as a colour through an
// Attribute node), "alpha" (float), "normal" (Vec3f, covariant normalize); none when empty.
void appendAttributeGrids(std::vector<VdbGrid>& grids, const SparseGrid& occupancy, const AttributeGrid& attributes);

// "sdf": the level set of result.sdf (hyvox/level_set.h), class level set, its active voxels'
// distances packed per leaf, its inside beyond the band as inactive leaves and tiles.
VdbGrid levelSetGrid(const VoxelizeResult& result);
// Whether the file of `result` has a "count" grid: when the method keeps points per voxel
// (the tessellation with tess_counts), even with none (an empty region of a farm job has one,
// as the other regions do), or when counts were given.
bool writesCountGrid(const VoxelizeResult& result);

// An upper estimate of the memory OpenVDB would need for a float grid of `leaves` leaves.
std::uint64_t fogGridMemUsageForLeaves(std::uint64_t leaves);

// The memory the density grid of `occupancy` takes as an OpenVDB grid (float leaves of 512
// values): what building it with OpenVDB (vdb_grid.h) needs.
std::uint64_t densityGridBytes(const SparseGrid& occupancy);
// What writeVdb holds beside the result for a grid of `leaves` leaves and `tile_bricks` bricks
// held as tiles, with `valued_voxels` voxels of `channels` attribute channels: the grids'
// leaves and tiles as the writer lists them, and the serialized grids (a density leaf is its
// mask and its compressed active values, about 220 bytes; an attribute value 4 bytes a
// channel) of one batch (writeVdbGrids). voxelize() estimates the write with it before any
// work (voxelize/memory_estimate.h).
double vdbWriterBytes(double leaves, double tile_bricks, double valued_voxels, double channels);
// ResourceError before anything is built when that grid and the result it is made from
// would not fit the write's memory budget.
void checkGridBudget(const VoxelizeResult& result, const WriteOptions& options);

// ---- densityGrid's template ----

template <typename Occupancy>
VdbGrid densityGrid(const Occupancy& occupancy) {
    VdbGrid grid;
    grid.name = "density";
    const auto& bricks = occupancy.bricks();
    const int side = 8;  // BrickLayout::kSide
    auto originOf = [&](std::uint64_t brick) {
        const std::array<std::int32_t, 3> b = bricks.at(brick);
        return std::array<std::int32_t, 3>{b[0] * side, b[1] * side, b[2] * side};
    };
    grid.leaves.reserve(occupancy.leaves().size());
    for (const auto& leaf : occupancy.leaves()) grid.leaves.push_back({originOf(leaf.brick), leaf.words});
    // Reserved exactly: a solid's millions of tile bricks would otherwise grow the list by doubling.
    std::size_t tile_bricks = 0;
    for (const auto& run : occupancy.tileRuns()) tile_bricks += run.end - run.begin;
    grid.tiles.reserve(tile_bricks);
    for (const auto& run : occupancy.tileRuns())
        for (std::uint64_t b = run.begin; b < run.end; ++b) grid.tiles.push_back({originOf(b), 1});
    return grid;
}

}  // namespace hyvox::vdb
