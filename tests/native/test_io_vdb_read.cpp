// SPDX-License-Identifier: GPL-3.0-or-later
// The .vdb reader (vdb/vdb_reader.h) against OpenVDB itself: grids OpenVDB builds and writes
// (fog volumes with per-voxel values and tiles of every level, a level set with its
// -background inside, a Vec3f grid with inactive values of its own), under every compression
// OpenVDB offers, must read back as OpenVDB's own trees: the same leaves, masks, active and
// inactive values, tiles (level, value, active), background, class and transform. Files it
// cannot read are refused with InvalidInput, never a crash.
#include <gtest/gtest.h>
#include <openvdb/io/File.h>
#include <openvdb/tools/LevelSetSphere.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "hyvox/errors.h"
#include "support/temp_dir.h"
#include "vdb/vdb_direct_writer.h"
#include "vdb/vdb_grid.h"
#include "vdb/vdb_reader.h"

namespace {

using hyvox::test::TempDir;
using hyvox::vdb::VdbReadGrid;

hyvox::GridSpec spec() {
    hyvox::GridSpec grid;
    grid.origin = {0.5, -2.0, 1.25};
    grid.voxel_size = 0.25;
    return grid;
}

// A fog volume: random voxels of random values around the origin (negative coordinates too),
// and active tiles at levels 1 to 3.
openvdb::FloatGrid::Ptr fogGrid() {
    auto grid = openvdb::FloatGrid::create(0.0f);
    grid->setName("density");
    grid->setGridClass(openvdb::GRID_FOG_VOLUME);
    grid->setTransform(hyvox::vdb::makeTransform(spec()));
    std::mt19937 rng(7);
    std::uniform_int_distribution<int> at(-40, 300);
    std::uniform_real_distribution<float> value(0.1f, 9.0f);
    auto accessor = grid->getAccessor();
    for (int n = 0; n < 4000; ++n) accessor.setValueOn(openvdb::Coord(at(rng), at(rng) / 4, at(rng) / 2), value(rng));
    grid->tree().addTile(1, openvdb::Coord(512, 0, 0), 2.5f, true);
    grid->tree().addTile(2, openvdb::Coord(1024, 128, 0), 3.5f, true);
    grid->tree().addTile(3, openvdb::Coord(8192, 0, -4096), 4.5f, true);
    grid->tree().addTile(1, openvdb::Coord(520, 0, 0), 7.0f, false);  // inactive, not the background
    return grid;
}

openvdb::FloatGrid::Ptr levelSet() {
    auto grid = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(6.0f, openvdb::Vec3f(1, 2, 3), 0.25f, 3.0f);
    grid->setName("sdf");
    return grid;
}

// Vec3f values; inactive voxels of two, three and more values besides the background, so that
// every inactive-value encoding appears.
openvdb::Vec3SGrid::Ptr vectorGrid() {
    auto grid = openvdb::Vec3SGrid::create(openvdb::Vec3s(0.0f));
    grid->setName("color");
    grid->setVectorType(openvdb::VEC_INVARIANT);
    grid->setTransform(hyvox::vdb::makeTransform(spec()));
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> value(-1.0f, 1.0f);
    auto accessor = grid->getAccessor();
    for (int leaf = 0; leaf < 6; ++leaf)
        for (int n = 0; n < 40; ++n) {
            const openvdb::Coord ijk(leaf * 8 + n % 8, (n / 8) % 8, n % 5);
            if (n % 3 == 0) {
                // Inactive with a value: leaf 0 one value, leaf 1 two, leaf 2 -background (zero:
                // the same), the others a different value each.
                const float v = leaf == 0 ? 5.0f : leaf == 1 ? float(n % 2) + 5.0f : float(leaf * 100 + n);
                accessor.setValueOff(ijk, openvdb::Vec3s(v, -v, 0.5f * v));
            } else {
                accessor.setValueOn(ijk, openvdb::Vec3s(value(rng), value(rng), value(rng)));
            }
        }
    return grid;
}

template <typename GridType>
std::array<float, 3> asFloats(const typename GridType::ValueType& v) {
    if constexpr (std::is_same_v<typename GridType::ValueType, float>)
        return {v, 0.0f, 0.0f};
    else
        return {v[0], v[1], v[2]};
}

// `read` holds exactly OpenVDB's tree of `grid`.
template <typename GridType>
void expectSameTree(const GridType& grid, const VdbReadGrid& read) {
    const int width = read.channels();
    EXPECT_EQ(read.name, grid.getName());
    // OpenVDB writes no class for GRID_UNKNOWN.
    const std::string grid_class =
        grid.getGridClass() == openvdb::GRID_UNKNOWN ? "" : openvdb::GridBase::gridClassToString(grid.getGridClass());
    EXPECT_EQ(read.metaText("class"), grid_class);
    const auto background = asFloats<GridType>(grid.background());
    EXPECT_TRUE(std::equal(background.begin(), background.begin() + width, read.background.begin()));

    std::map<std::array<std::int32_t, 3>, const VdbReadGrid::Leaf*> leaves;
    for (const auto& leaf : read.leaves) leaves[leaf.origin] = &leaf;
    ASSERT_EQ(leaves.size(), grid.tree().leafCount());
    for (auto leaf = grid.tree().cbeginLeaf(); leaf; ++leaf) {
        const openvdb::Coord o = leaf->origin();
        const auto found = leaves.find({o.x(), o.y(), o.z()});
        ASSERT_NE(found, leaves.end());
        const VdbReadGrid::Leaf& got = *found->second;
        for (int w = 0; w < 8; ++w) ASSERT_EQ(got.mask[w], leaf->getValueMask().template getWord<std::uint64_t>(w));
        std::uint64_t active = got.first;
        for (openvdb::Index v = 0; v < 512; ++v) {
            const auto want = asFloats<GridType>(leaf->getValue(v));
            const float* value = nullptr;
            if (leaf->isValueOn(v))
                value =
                    read.uniform ? read.uniform_value.data() : &read.values[std::size_t(active++) * std::size_t(width)];
            else
                value = got.inactive >= 0
                    ? &read.inactive_values[(std::size_t(got.inactive) * 512 + v) * std::size_t(width)]
                    : read.background.data();
            ASSERT_TRUE(std::equal(want.begin(), want.begin() + width, value)) << read.name << " voxel " << v;
        }
    }
    // Tiles: active ones, and inactive ones of another value than the background.
    using Tile = std::tuple<std::array<std::int32_t, 3>, int, std::array<float, 3>>;
    std::vector<Tile> on, off;
    for (auto it = grid.cbeginValueAll(); it; ++it) {
        if (it.isVoxelValue()) continue;
        const auto value = asFloats<GridType>(*it);
        const openvdb::Coord c = it.getCoord();
        if (it.isValueOn())
            on.emplace_back(std::array<std::int32_t, 3>{c.x(), c.y(), c.z()}, int(it.getLevel()), value);
        else if (!std::equal(value.begin(), value.begin() + width, background.begin()))
            off.emplace_back(std::array<std::int32_t, 3>{c.x(), c.y(), c.z()}, int(it.getLevel()), value);
    }
    auto tiles = [](const std::vector<hyvox::vdb::VdbTile>& from) {
        std::vector<Tile> out;
        for (const auto& t : from) out.emplace_back(t.origin, t.level, t.value);
        std::sort(out.begin(), out.end());
        return out;
    };
    std::sort(on.begin(), on.end());
    std::sort(off.begin(), off.end());
    EXPECT_EQ(tiles(read.tiles), on) << read.name;
    EXPECT_EQ(tiles(read.inactive_tiles), off) << read.name;
}

TEST(IoVdbRead, EveryCompressionReadsBackAsOpenVdbsTrees) {
    hyvox::vdb::initializeOpenVdb();
    TempDir dir;
    const auto fog = fogGrid();
    const auto sdf = levelSet();
    const auto color = vectorGrid();
    ASSERT_GT(fog->tree().activeTileCount(), 0u);
    const std::string transform = hyvox::vdb::vdbTransformBytes(spec());
    using namespace openvdb::io;
    for (const std::uint32_t compression :
         {std::uint32_t(COMPRESS_NONE), std::uint32_t(COMPRESS_ZIP), std::uint32_t(COMPRESS_BLOSC),
          std::uint32_t(COMPRESS_ACTIVE_MASK), std::uint32_t(COMPRESS_ZIP | COMPRESS_ACTIVE_MASK),
          std::uint32_t(COMPRESS_BLOSC | COMPRESS_ACTIVE_MASK)}) {
        SCOPED_TRACE("compression " + std::to_string(compression));
        const std::string path = (dir.path / ("grids" + std::to_string(compression) + ".vdb")).string();
        openvdb::io::File file(path);
        file.setCompression(compression);
        file.write({fog, sdf, color});
        file.close();
        const hyvox::vdb::VdbFile read = hyvox::vdb::readVdbFile(path);
        ASSERT_EQ(read.grids.size(), 3u);
        expectSameTree(*fog, read.grids[0]);
        expectSameTree(*sdf, read.grids[1]);
        expectSameTree(*color, read.grids[2]);
        EXPECT_FALSE(read.grids[0].uniform);
        EXPECT_FALSE(read.grids[1].inactive_tiles.empty());  // the sphere's inside
        EXPECT_EQ(read.grids[0].transform, transform);       // hyvox's transform, as OpenVDB writes it
        EXPECT_EQ(read.grids[2].metaText("vector_type"), "invariant");
    }
}

TEST(IoVdbRead, OneValueOnEveryLeafIsKeptOnce) {
    hyvox::vdb::initializeOpenVdb();
    TempDir dir;
    auto grid = openvdb::FloatGrid::create(0.0f);
    grid->setName("density");
    auto accessor = grid->getAccessor();
    for (int n = 0; n < 300; ++n) accessor.setValueOn(openvdb::Coord(n, n / 3, 2 * n), 1.0f);
    const std::string path = (dir.path / "ones.vdb").string();
    openvdb::io::File(path).write({grid});
    const VdbReadGrid read = hyvox::vdb::readVdbFile(path).grids[0];
    EXPECT_TRUE(read.uniform);
    EXPECT_EQ(read.uniform_value[0], 1.0f);
    EXPECT_TRUE(read.values.empty());
    EXPECT_EQ(read.activeLeafVoxels(), 300u);
}

std::string fileBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST(IoVdbRead, FilesItCannotReadAreRefused) {
    hyvox::vdb::initializeOpenVdb();
    TempDir dir;
    auto refused = [&](const std::string& path, const std::string& why) {
        try {
            hyvox::vdb::readVdbFile(path);
            ADD_FAILURE() << path << " was read";
        } catch (const hyvox::InvalidInput& e) {
            EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
        }
    };
    const std::string half = (dir.path / "half.vdb").string();
    auto fog = fogGrid();
    fog->setSaveFloatAsHalf(true);
    openvdb::io::File(half).write({fog});
    refused(half, "half floats");
    const std::string ints = (dir.path / "ints.vdb").string();
    openvdb::io::File(ints).write({openvdb::Int32Grid::create(3)});
    refused(ints, "Tree_int32_5_4_3");
    refused((dir.path / "missing.vdb").string(), "cannot open");
    refused(dir.write("text.vdb", "not a vdb file at all").string(), "magic number");

    // Every cut of a real file, and bytes overwritten anywhere: an error, never a crash.
    const std::string good = (dir.path / "good.vdb").string();
    openvdb::io::File(good).write({fogGrid(), vectorGrid(), levelSet()});
    const std::string bytes = fileBytes(good);
    for (std::size_t cut = 0; cut < bytes.size(); cut += 1 + cut / 7)
        refused(dir.write("cut.vdb", bytes.substr(0, cut)).string(), "is not a .vdb file hyvox can read");
    // Flipped bytes: a clear refusal or a file read, never a crash (ASan and UBSan watch).
    std::mt19937 rng(5);
    int refusals = 0;
    for (int trial = 0; trial < 100; ++trial) {
        std::string broken = bytes;
        for (int n = 0; n < 4; ++n) broken[rng() % broken.size()] = char(rng());
        try {
            hyvox::vdb::readVdbFile(dir.write("broken.vdb", broken).string());
        } catch (const hyvox::InvalidInput&) {
            ++refusals;
        }
    }
    EXPECT_GT(refusals, 0);
}

}  // namespace
