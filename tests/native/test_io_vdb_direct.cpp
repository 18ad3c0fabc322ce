// SPDX-License-Identifier: GPL-3.0-or-later
// The directly serialized .vdb (vdb/vdb_direct_writer.h) against OpenVDB's own writer: both
// files read back with OpenVDB must hold the same grid (tree shape, every leaf's mask and
// values, background, transform) and the same metadata, on grids spanning several upper and
// lower internal nodes, full and empty leaves, and an empty grid.
#include <gtest/gtest.h>
#include <openvdb/io/File.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <iterator>
#include <random>
#include <string>

#include "hyvox/vdb.h"
#include "support/temp_dir.h"
#include "support/vdb_grid_checks.h"
#include "vdb/vdb_direct_writer.h"
#include "vdb/vdb_grid.h"

namespace {

using hyvox::test::expectSameGrids;
using hyvox::test::readVdbGrid;
using hyvox::test::TempDir;

// Bits scattered with probability `fill` over a small grid, plus voxels far apart in a large
// one (several 4096³ upper nodes and 128³ lower nodes), origin off the lattice.
hyvox::VoxelizeResult makeResult(std::array<std::int32_t, 3> dims, double fill, std::uint32_t seed,
                                 int scattered = 300) {
    hyvox::VoxelizeResult r;
    r.grid.origin = {-1.25, 0.5, 3.0};
    r.grid.voxel_size = 0.1;
    r.grid.dims = dims;
    r.occupancy = hyvox::SparseGrid(dims);
    std::mt19937 rng(seed);
    std::bernoulli_distribution on(fill);
    for (int i = 0; i < std::min(dims[0], 40); ++i)
        for (int j = 0; j < std::min(dims[1], 24); ++j)
            for (int k = 0; k < std::min(dims[2], 17); ++k)
                if (on(rng)) r.occupancy.set(i, j, k);
    std::uniform_int_distribution<int> x(0, dims[0] - 1), y(0, dims[1] - 1), z(0, dims[2] - 1);
    if (fill > 0)
        for (int n = 0; n < scattered; ++n) r.occupancy.set(x(rng), y(rng), z(rng));
    r.stats.method = "cpu";
    r.stats.mode = "thin";
    r.stats.voxel_count = r.occupancy.count();
    return r;
}

// The bytes of the first grid's leaf buffers: GridDescriptor's block and end positions, read
// after the header (magic, versions, offsets flag, UUID, no file metadata, grid count) and
// the descriptor's three strings.
std::string firstGridBuffers(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::size_t at = 8 + 4 + 4 + 4 + 1 + 36 + 4 + 4;
    for (int s = 0; s < 3; ++s) {
        std::uint32_t length = 0;
        std::memcpy(&length, &bytes.at(at), 4);
        at += 4 + length;
    }
    std::int64_t block = 0, end = 0;
    std::memcpy(&block, &bytes.at(at + 8), 8);
    std::memcpy(&end, &bytes.at(at + 16), 8);
    EXPECT_LE(std::size_t(end), bytes.size());
    return bytes.substr(std::size_t(block), std::size_t(end - block));
}

void checkAgainstOpenVdb(const hyvox::VoxelizeResult& r, int threads) {
    TempDir dir;
    const std::string direct_path = (dir.path / "direct.vdb").string(),
                      reference_path = (dir.path / "openvdb.vdb").string();
    hyvox::WriteOptions write;
    write.threads = threads;
    hyvox::writeVdb(r, direct_path, write);
    const openvdb::GridPtrVec grids = hyvox::vdb::makeGrids(r);
    hyvox::vdb::writeGridsAtomic(openvdb::GridCPtrVec(grids.begin(), grids.end()), reference_path);
    hyvox::vdb::initializeOpenVdb();
    const auto direct = readVdbGrid<openvdb::FloatGrid>(direct_path, "density");
    const auto reference = readVdbGrid<openvdb::FloatGrid>(reference_path, "density");
    ASSERT_TRUE(direct && reference);
    EXPECT_EQ(direct->metaValue<std::string>("file_compression"), "blosc + active values");
    // Compressed as OpenVDB compresses: the first grid's leaf buffers (blosc blocks) are
    // byte for byte OpenVDB's. (The files' sizes differ by OpenVDB's "file_delayed_load"
    // metadata, which the direct writer leaves out: readers do without it.)
    EXPECT_EQ(firstGridBuffers(direct_path), firstGridBuffers(reference_path));
    expectSameGrids(*direct, *reference);
    // The memory figure the direct writer states is OpenVDB's own for the built grid.
    EXPECT_EQ(hyvox::vdb::vdbTreeMemUsage(hyvox::vdb::densityGrid(r.occupancy)), grids[0]->memUsage());
    if (r.counts.empty()) return;
    const auto direct_count = readVdbGrid<openvdb::FloatGrid>(direct_path, "count");
    const auto reference_count = readVdbGrid<openvdb::FloatGrid>(reference_path, "count");
    ASSERT_TRUE(direct_count && reference_count);
    expectSameGrids(*direct_count, *reference_count);
}

}  // namespace

TEST(IoVdbDirect, SmallGridsEqualOpenVdbsFile) {
    for (double fill : {0.0, 0.03, 0.5, 1.0}) {
        SCOPED_TRACE(fill);
        checkAgainstOpenVdb(makeResult({37, 20, 9}, fill, 5), 0);
    }
}

TEST(IoVdbDirect, GridsOverManyInternalNodesEqualOpenVdbsFile) {
    // 9000 > 2 × 4096 along x: three upper nodes; lower nodes scattered in each.
    checkAgainstOpenVdb(makeResult({9000, 300, 4200}, 0.2, 9), 0);
    checkAgainstOpenVdb(makeResult({9000, 300, 4200}, 0.2, 9), 1);
}

TEST(IoVdbDirect, CountGridEqualsOpenVdbsFile) {
    auto r = makeResult({9000, 300, 4200}, 0.1, 4);
    std::mt19937 rng(3);
    std::uniform_int_distribution<std::uint32_t> count(1, 1000);
    for (const auto& ijk : r.occupancy.coords()) r.counts.push_back({ijk[0], ijk[1], ijk[2], count(rng)});
    std::shuffle(r.counts.begin(), r.counts.end(), rng);  // any order
    checkAgainstOpenVdb(r, 0);
}

TEST(IoVdbDirect, LeavesOverSeveralWriteBatchesEqualOpenVdbsFile) {
    // Leaves scattered one voxel each, more than two batches of the writer (it compresses and
    // writes kVdbLeavesPerBatch at a time and puts each grid's end position in afterwards),
    // with a count grid after them.
    const int scattered = int(2 * hyvox::vdb::kVdbLeavesPerBatch + 1000);
    auto r = makeResult({6000, 2000, 3000}, 0.1, 6, scattered);
    ASSERT_GT(r.occupancy.leafCount(), 2 * hyvox::vdb::kVdbLeavesPerBatch);
    for (const auto& ijk : r.occupancy.coords()) r.counts.push_back({ijk[0], ijk[1], ijk[2], 7u});
    checkAgainstOpenVdb(r, 2);
}

TEST(IoVdbDirect, EmptyGridEqualsOpenVdbsFile) { checkAgainstOpenVdb(makeResult({5, 6, 7}, 0.0, 1), 0); }
