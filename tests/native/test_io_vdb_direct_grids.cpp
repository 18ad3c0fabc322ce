// SPDX-License-Identifier: GPL-3.0-or-later
// The direct .vdb writer's tiles and value grids (vdb/vdb_direct_writer.h) against OpenVDB:
// a grid of leaves and active tiles (as a solid's interior makes them, merged upwards as
// prune() merges them), and Vec3f / float attribute grids with per-voxel values, each
// written by both writers and read back with OpenVDB, must hold the same trees (leaves,
// tiles and their levels, every active value), types and metadata.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include "hyvox/errors.h"
#include "hyvox/vdb.h"
#include "support/temp_dir.h"
#include "support/vdb_grid_checks.h"
#include "vdb/vdb_direct_writer.h"
#include "vdb/vdb_grid.h"

namespace {

using hyvox::test::expectSameGrids;
using hyvox::test::TempDir;
using hyvox::vdb::VdbGrid;
using hyvox::vdb::VdbValueType;

hyvox::VoxelizeResult makeResult(std::array<std::int32_t, 3> dims, double fill, std::uint32_t seed,
                                 std::array<std::int32_t, 3> box) {
    hyvox::VoxelizeResult r;
    r.grid.origin = {0.5, -2.0, 1.25};
    r.grid.voxel_size = 0.25;
    r.grid.dims = dims;
    r.occupancy = hyvox::SparseGrid(dims);
    std::mt19937 rng(seed);
    std::bernoulli_distribution on(fill);
    for (int i = 0; i < box[0]; ++i)
        for (int j = 0; j < box[1]; ++j)
            for (int k = 0; k < box[2]; ++k)
                if (on(rng)) r.occupancy.set(i, j, k);
    r.stats.method = "cpu";
    r.stats.mode = "solid";
    return r;
}

void writeFile(const std::string& path, const hyvox::VoxelizeResult& r, const std::vector<VdbGrid>& grids,
               int threads) {
    std::ofstream out(path, std::ios::binary);
    hyvox::vdb::writeVdbGrids(out, r, grids, threads);
}

// The direct writer's bytes of `grids`, in memory (a string stream is seekable, as the writer needs).
std::string writtenBytes(const hyvox::VoxelizeResult& r, const std::vector<VdbGrid>& grids) {
    std::ostringstream out;
    hyvox::vdb::writeVdbGrids(out, r, grids, 1);
    return out.str();
}

// An empty density grid from makeGrids: the transform and hyvox metadata OpenVDB's writer
// gets for every grid of `r`.
openvdb::FloatGrid::Ptr referenceShell(const hyvox::VoxelizeResult& r) {
    hyvox::VoxelizeResult empty = r;
    empty.occupancy = hyvox::SparseGrid(r.grid.dims);
    return openvdb::gridPtrCast<openvdb::FloatGrid>(hyvox::vdb::makeGrids(empty)[0]);
}

// The solid branch's SparseGrid stand-in: its leaves, plus runs of whole bricks as tiles.
struct OccupancyWithTiles {
    struct TileRun {
        std::uint64_t begin, end;
    };
    const hyvox::SparseGrid* grid;
    std::vector<TileRun> runs;
    const hyvox::BrickLayout& bricks() const { return grid->bricks(); }
    const std::vector<hyvox::SparseGrid::Leaf>& leaves() const { return grid->leaves(); }
    const std::vector<TileRun>& tileRuns() const { return runs; }
};

}  // namespace

TEST(IoVdbDirectGrids, LeavesAndTilesEqualOpenVdbsPrunedTree) {
    // Dims 300 × 260 × 140: lower nodes 128³; surface voxels in x, y < 16, z < 140 (leaves),
    // and whole bricks as tiles: a full 128³ lower node (4096 tiles, written as one level-2
    // tile), a partial one, and bricks next to leaves.
    hyvox::VoxelizeResult r = makeResult({300, 260, 140}, 0.4, 7, {16, 16, 140});
    const hyvox::BrickLayout& bricks = r.occupancy.bricks();
    OccupancyWithTiles occupancy{&r.occupancy, {}};
    auto brickIndex = [&](int bx, int by, int bz) { return std::uint64_t(bricks.index(bx, by, bz)); };
    std::vector<std::uint64_t> tile_bricks;
    for (int bx = 16; bx < 32; ++bx)  // the lower node at (128, 0, 0): all 4096 bricks
        for (int by = 0; by < 16; ++by)
            for (int bz = 0; bz < 16; ++bz) tile_bricks.push_back(brickIndex(bx, by, bz));
    for (int bz = 0; bz < 10; ++bz) tile_bricks.push_back(brickIndex(5, 20, bz));  // part of the node at (0, 128, 0)
    tile_bricks.push_back(brickIndex(2, 1, 16));                                   // next to the leaves
    std::sort(tile_bricks.begin(), tile_bricks.end());
    for (std::uint64_t b : tile_bricks) occupancy.runs.push_back({b, b + 1});

    const VdbGrid density = hyvox::vdb::densityGrid(occupancy);
    ASSERT_EQ(density.tiles.size(), tile_bricks.size());
    TempDir dir;
    const std::string direct_path = (dir.path / "direct.vdb").string(),
                      reference_path = (dir.path / "openvdb.vdb").string();
    writeFile(direct_path, r, {density}, 0);

    // OpenVDB: the leaves, every brick as a level-1 tile, then prune(), as the solid mode does.
    auto reference = referenceShell(r);
    {
        openvdb::FloatGrid::Accessor accessor(reference->tree());
        for (const auto& ijk : r.occupancy.coords()) accessor.setValue(openvdb::Coord(ijk[0], ijk[1], ijk[2]), 1.0f);
        for (std::uint64_t b : tile_bricks) {
            const auto at = bricks.at(b);
            accessor.addTile(1, openvdb::Coord(at[0] * 8, at[1] * 8, at[2] * 8), 1.0f, true);
        }
    }
    reference->tree().prune();
    EXPECT_EQ(reference->tree().activeTileCount(), tile_bricks.size() - 4096 + 1);  // the full node merged
    hyvox::vdb::writeGridsAtomic({reference}, reference_path);

    hyvox::vdb::initializeOpenVdb();
    const auto direct = hyvox::test::readVdbGrid<openvdb::FloatGrid>(direct_path, "density");
    const auto read_reference = hyvox::test::readVdbGrid<openvdb::FloatGrid>(reference_path, "density");
    ASSERT_TRUE(direct && read_reference);
    expectSameGrids(*direct, *read_reference);
    EXPECT_EQ(hyvox::vdb::vdbTreeMemUsage(density), reference->memUsage());
}

TEST(IoVdbDirectGrids, TilesOfOtherValuesAndLevelsEqualOpenVdbs) {
    // Tiles given at every level, with values other than 1, and a Vec3f grid of tiles.
    hyvox::VoxelizeResult r = makeResult({9000, 200, 200}, 0.3, 3, {12, 12, 12});
    VdbGrid grid = hyvox::vdb::densityGrid(r.occupancy);
    grid.tiles = {{{64, 0, 0}, 1, {2.5f, 0, 0}},
                  {{72, 0, 0}, 1, {-1.0f, 0, 0}},
                  {{128, 128, 0}, 2, {3.0f, 0, 0}},
                  {{4096, 0, 0}, 3, {0.5f, 0, 0}}};
    auto reference = referenceShell(r);
    for (const auto& ijk : r.occupancy.coords())
        reference->tree().setValue(openvdb::Coord(ijk[0], ijk[1], ijk[2]), 1.0f);
    for (const auto& tile : grid.tiles)
        reference->tree().addTile(openvdb::Index(tile.level),
                                  openvdb::Coord(tile.origin[0], tile.origin[1], tile.origin[2]), tile.value[0], true);

    VdbGrid vectors = grid;
    vectors.name = "velocity";
    vectors.type = VdbValueType::Vec3f;
    vectors.grid_class.clear();
    vectors.vector_type = "contravariant relative";
    vectors.fill = {0.25f, -4.0f, 8.0f};
    for (auto& tile : vectors.tiles) tile.value = {tile.value[0], 1.0f, -tile.value[0]};
    auto reference_vectors = openvdb::Vec3SGrid::create(openvdb::Vec3s(0.0f));
    for (auto it = reference->beginMeta(); it != reference->endMeta(); ++it)
        if (it->first != "class") reference_vectors->insertMeta(it->first, *it->second);
    reference_vectors->setName("velocity");
    reference_vectors->setTransform(reference->transform().copy());
    reference_vectors->setVectorType(openvdb::VEC_CONTRAVARIANT_RELATIVE);
    for (const auto& ijk : r.occupancy.coords())
        reference_vectors->tree().setValue(openvdb::Coord(ijk[0], ijk[1], ijk[2]), openvdb::Vec3s(0.25f, -4.0f, 8.0f));
    for (const auto& tile : vectors.tiles)
        reference_vectors->tree().addTile(openvdb::Index(tile.level),
                                          openvdb::Coord(tile.origin[0], tile.origin[1], tile.origin[2]),
                                          openvdb::Vec3s(tile.value[0], tile.value[1], tile.value[2]), true);

    TempDir dir;
    const std::string direct_path = (dir.path / "direct.vdb").string(),
                      reference_path = (dir.path / "openvdb.vdb").string();
    writeFile(direct_path, r, {grid, vectors}, 2);
    hyvox::vdb::writeGridsAtomic({reference, reference_vectors}, reference_path);
    const auto direct = hyvox::test::readVdbGrid<openvdb::FloatGrid>(direct_path, "density");
    const auto read_reference = hyvox::test::readVdbGrid<openvdb::FloatGrid>(reference_path, "density");
    ASSERT_TRUE(direct && read_reference);
    EXPECT_EQ(read_reference->tree().activeTileCount(), 4u);
    expectSameGrids(*direct, *read_reference);
    const auto direct_vectors = hyvox::test::readVdbGrid<openvdb::Vec3SGrid>(direct_path, "velocity");
    const auto read_reference_vectors = hyvox::test::readVdbGrid<openvdb::Vec3SGrid>(reference_path, "velocity");
    ASSERT_TRUE(direct_vectors && read_reference_vectors);
    expectSameGrids(*direct_vectors, *read_reference_vectors);
}

TEST(IoVdbDirectGrids, AttributeGridsEqualOpenVdbs) {
    // Several upper nodes; random values per voxel, in coords() order, 7 channels each.
    hyvox::VoxelizeResult r = makeResult({5000, 300, 140}, 0.2, 11, {40, 30, 20});
    std::mt19937 rng(5);
    std::uniform_int_distribution<int> x(0, 4999), y(0, 299), z(0, 139);
    for (int n = 0; n < 500; ++n) r.occupancy.set(x(rng), y(rng), z(rng));
    const auto coords = r.occupancy.coords();
    r.attributes.color = r.attributes.alpha = r.attributes.normal = true;
    ASSERT_EQ(r.attributes.channels(), 7);
    std::uniform_real_distribution<float> value(-2.0f, 2.0f);
    for (std::size_t n = 0; n < coords.size() * 7; ++n) r.attributes.values.push_back(value(rng));

    // OpenVDB, voxel by voxel through an accessor.
    auto density = referenceShell(r);
    auto vectorGrid = [&](const char* name, int offset, openvdb::VecType type) {
        auto grid = openvdb::Vec3SGrid::create(openvdb::Vec3s(0.0f));
        for (auto it = density->beginMeta(); it != density->endMeta(); ++it)
            if (it->first != "class") grid->insertMeta(it->first, *it->second);
        grid->setName(name);
        grid->setTransform(density->transform().copy());
        grid->setVectorType(type);
        openvdb::Vec3SGrid::Accessor accessor(grid->tree());
        for (std::size_t v = 0; v < coords.size(); ++v) {
            const float* c = &r.attributes.values[v * 7 + std::size_t(offset)];
            accessor.setValue(openvdb::Coord(coords[v][0], coords[v][1], coords[v][2]),
                              openvdb::Vec3s(c[0], c[1], c[2]));
        }
        return grid;
    };
    auto color = vectorGrid("color", 0, openvdb::VEC_INVARIANT);
    auto normal = vectorGrid("normal", 4, openvdb::VEC_COVARIANT_NORMALIZE);
    auto alpha = openvdb::FloatGrid::create(0.0f);
    for (auto it = density->beginMeta(); it != density->endMeta(); ++it)
        if (it->first != "class") alpha->insertMeta(it->first, *it->second);
    alpha->setName("alpha");
    alpha->setTransform(density->transform().copy());
    for (std::size_t v = 0; v < coords.size(); ++v)
        alpha->tree().setValue(openvdb::Coord(coords[v][0], coords[v][1], coords[v][2]),
                               r.attributes.values[v * 7 + 3]);
    {
        openvdb::FloatGrid::Accessor accessor(density->tree());
        for (const auto& ijk : coords) accessor.setValue(openvdb::Coord(ijk[0], ijk[1], ijk[2]), 1.0f);
    }

    // writeVdb (the direct writer) against the voxel-by-voxel grids written by OpenVDB, and
    // against makeGrids (OpenVDB's own attribute grids, the Python module's path).
    TempDir dir;
    const std::string direct_path = (dir.path / "direct.vdb").string(),
                      reference_path = (dir.path / "openvdb.vdb").string(),
                      made_path = (dir.path / "made.vdb").string();
    hyvox::writeVdb(r, direct_path);
    hyvox::vdb::writeGridsAtomic({density, color, alpha, normal}, reference_path);
    const openvdb::GridPtrVec made = hyvox::vdb::makeGrids(r);
    hyvox::vdb::writeGridsAtomic(openvdb::GridCPtrVec(made.begin(), made.end()), made_path);
    for (const std::string& other : {reference_path, made_path}) {
        SCOPED_TRACE(other);
        for (const char* name : {"color", "normal"}) {
            SCOPED_TRACE(name);
            const auto direct = hyvox::test::readVdbGrid<openvdb::Vec3SGrid>(direct_path, name);
            const auto reference = hyvox::test::readVdbGrid<openvdb::Vec3SGrid>(other, name);
            ASSERT_TRUE(direct && reference);
            EXPECT_EQ(reference->activeVoxelCount(), coords.size());
            expectSameGrids(*direct, *reference);
        }
        for (const char* name : {"density", "alpha"}) {
            SCOPED_TRACE(name);
            const auto direct = hyvox::test::readVdbGrid<openvdb::FloatGrid>(direct_path, name);
            const auto reference = hyvox::test::readVdbGrid<openvdb::FloatGrid>(other, name);
            ASSERT_TRUE(direct && reference);
            expectSameGrids(*direct, *reference);
        }
    }
}

TEST(IoVdbDirectGrids, LevelSetEqualsOpenVdbs) {
    // A level set over several upper nodes: leaves with active distances and inactive voxels
    // inside and outside (every metadata case: none inactive, outside only, inside only, both),
    // leaves of inactive voxels only, inside tiles filling whole lower nodes (written as their
    // upper node's tiles) and others beside empty slots (a node table selecting +background).
    hyvox::VoxelizeResult r = makeResult({4600, 300, 140}, 0.0, 1, {0, 0, 0});
    const hyvox::BrickLayout bricks = r.grid.bricks();
    hyvox::LevelSetGrid& sdf = r.sdf;
    sdf.background = 0.75f;
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> distance(-0.74f, 0.74f);
    auto addLeaf = [&](std::array<int, 3> b, double active, double inside) {
        hyvox::LevelSetGrid::Leaf leaf{};
        leaf.brick = bricks.index(b[0], b[1], b[2]);
        leaf.first = sdf.values.size();
        std::bernoulli_distribution is_active(active), is_inside(inside);
        for (int v = 0; v < 512; ++v) {
            if (is_inside(rng)) leaf.inside[v >> 6] |= std::uint64_t(1) << (v & 63);
            if (!is_active(rng)) continue;
            leaf.active[v >> 6] |= std::uint64_t(1) << (v & 63);
            sdf.values.push_back(distance(rng));
        }
        sdf.leaves.push_back(leaf);
    };
    addLeaf({0, 0, 0}, 1.0, 0.5);      // all active
    addLeaf({0, 0, 1}, 0.3, 0.0);      // inactive outside only
    addLeaf({0, 0, 2}, 0.3, 1.0);      // inactive inside only
    addLeaf({0, 1, 0}, 0.3, 0.5);      // both
    addLeaf({0, 1, 1}, 0.0, 0.5);      // no active voxel
    addLeaf({560, 30, 17}, 0.5, 0.5);  // in another upper node
    // Inside tiles: two whole lower nodes (16³ bricks each, from brick (16, 0, 0) and (16, 16,
    // 0) on), and a few bricks of a third beside its empty slots.
    auto addRun = [&](std::array<int, 3> b, int count) {
        const std::uint64_t first = bricks.index(b[0], b[1], b[2]);
        sdf.inside_runs.push_back({first, first + std::uint64_t(count)});
    };
    for (int bx = 16; bx < 32; ++bx)
        for (int by = 0; by < 32; ++by) addRun({bx, by, 0}, 16);
    addRun({40, 3, 5}, 4);
    addRun({40, 4, 5}, 2);
    std::sort(sdf.inside_runs.begin(), sdf.inside_runs.end(),
              [](const auto& a, const auto& b) { return a.begin < b.begin; });

    // OpenVDB, voxel by voxel.
    auto density = referenceShell(r);
    auto reference = openvdb::FloatGrid::create(sdf.background);
    for (auto it = density->beginMeta(); it != density->endMeta(); ++it)
        if (it->first != "class") reference->insertMeta(it->first, *it->second);
    reference->setName("sdf");
    reference->setGridClass(openvdb::GRID_LEVEL_SET);
    reference->setTransform(density->transform().copy());
    {
        openvdb::FloatGrid::Accessor accessor(reference->tree());
        for (const auto& leaf : sdf.leaves) {
            const auto b = bricks.at(leaf.brick);
            std::size_t next = leaf.first;
            for (int v = 0; v < 512; ++v) {
                const openvdb::Coord c(8 * b[0] + (v >> 6), 8 * b[1] + ((v >> 3) & 7), 8 * b[2] + (v & 7));
                if ((leaf.active[v >> 6] >> (v & 63)) & 1)
                    accessor.setValueOn(c, sdf.values[next++]);
                else
                    accessor.setValueOff(c, (leaf.inside[v >> 6] >> (v & 63)) & 1 ? -sdf.background : sdf.background);
            }
        }
        for (const auto& run : sdf.inside_runs)
            for (std::uint64_t brick = run.begin; brick < run.end; ++brick) {
                const auto b = bricks.at(brick);
                accessor.addTile(1, openvdb::Coord(8 * b[0], 8 * b[1], 8 * b[2]), -sdf.background, false);
            }
        reference->tree().prune();
    }
    TempDir dir;
    const std::string direct_path = (dir.path / "direct.vdb").string(),
                      reference_path = (dir.path / "openvdb.vdb").string(),
                      made_path = (dir.path / "made.vdb").string();
    hyvox::writeVdb(r, direct_path);
    hyvox::vdb::writeGridsAtomic({density, reference}, reference_path);
    const openvdb::GridPtrVec made = hyvox::vdb::makeGrids(r);
    hyvox::vdb::writeGridsAtomic(openvdb::GridCPtrVec(made.begin(), made.end()), made_path);
    for (const std::string& other : {reference_path, made_path}) {
        SCOPED_TRACE(other);
        const auto direct = hyvox::test::readVdbGrid<openvdb::FloatGrid>(direct_path, "sdf");
        const auto read = hyvox::test::readVdbGrid<openvdb::FloatGrid>(other, "sdf");
        ASSERT_TRUE(direct && read);
        EXPECT_EQ(read->activeVoxelCount(), sdf.activeCount());
        EXPECT_EQ(read->tree().getValueDepth(openvdb::Coord(130, 7, 9)), 1);  // a lower node's tile of the upper node
        EXPECT_EQ(read->tree().getValue(openvdb::Coord(130, 7, 9)), -sdf.background);
        EXPECT_EQ(read->tree().getValue(openvdb::Coord(321, 35, 47)), -sdf.background);  // brick (40, 4, 5)
        EXPECT_EQ(read->tree().getValue(openvdb::Coord(321, 35, 60)), sdf.background);   // beside it: outside
        expectSameGrids(*direct, *read);
    }
}

TEST(IoVdbDirectGrids, OverlapsAndOffLatticeTilesAreRefused) {
    hyvox::VoxelizeResult r = makeResult({64, 64, 64}, 0.5, 2, {8, 8, 8});
    VdbGrid grid = hyvox::vdb::densityGrid(r.occupancy);
    grid.tiles = {{{0, 0, 0}, 1}};  // on the leaf at 0
    EXPECT_THROW(writtenBytes(r, {grid}), hyvox::InvalidInput);
    grid.tiles = {{{0, 0, 0}, 2}};  // over the lower node that holds that leaf
    EXPECT_THROW(writtenBytes(r, {grid}), hyvox::InvalidInput);
    grid.tiles = {{{12, 0, 0}, 1}};  // off the 8-voxel lattice
    EXPECT_THROW(writtenBytes(r, {grid}), hyvox::InvalidInput);
    grid.tiles = {{{16, 0, 0}, 1}, {{16, 0, 0}, 1}};  // twice
    EXPECT_THROW(writtenBytes(r, {grid}), hyvox::InvalidInput);
    grid.tiles = {{{16, 0, 0}, 1}};
    EXPECT_NO_THROW(writtenBytes(r, {grid}));
}
