// SPDX-License-Identifier: GPL-3.0-or-later
// OpenVDB output: the leaf-copy tree equals a voxel-by-voxel one, the file reads back with
// voxel centres where docs/design.md puts them, and writes are atomic.
#include <gtest/gtest.h>
#include <openvdb/io/File.h>
#include <sys/resource.h>

#include <algorithm>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <random>
#include <sstream>

#include "hyvox/errors.h"
#include "hyvox/vdb.h"
#include "support/temp_dir.h"
#include "vdb/vdb_grid.h"

namespace fs = std::filesystem;

namespace {

// A result with bits scattered over a grid whose dims are not multiples of 8 (partial
// bricks at the far ends) and an origin off the integer lattice.
hyvox::VoxelizeResult sampleResult(std::uint32_t seed = 7, double fill = 0.05) {
    hyvox::VoxelizeResult r;
    r.grid.origin = {-1.25, 0.5, 3.0};
    r.grid.voxel_size = 0.1;
    r.grid.dims = {37, 20, 9};
    r.occupancy = hyvox::SparseGrid(r.grid.dims);
    std::mt19937 rng(seed);
    std::bernoulli_distribution on(fill);
    for (int i = 0; i < 37; ++i)
        for (int j = 0; j < 20; ++j)
            for (int k = 0; k < 9; ++k)
                if (on(rng)) r.occupancy.set(i, j, k);
    // Corners of the grid, so the far partial bricks are exercised.
    r.occupancy.set(0, 0, 0);
    r.occupancy.set(36, 19, 8);
    r.stats.method = "cpu";
    r.stats.mode = "conservative";
    r.stats.voxel_count = r.occupancy.count();
    return r;
}

using hyvox::test::TempDir;

using Ijk = std::array<std::int32_t, 3>;

std::vector<Ijk> activeCoords(const openvdb::FloatGrid& grid) {
    std::vector<Ijk> out;
    for (auto it = grid.cbeginValueOn(); it; ++it) {
        const openvdb::Coord c = it.getCoord();
        out.push_back({c.x(), c.y(), c.z()});
    }
    std::sort(out.begin(), out.end());
    return out;
}

openvdb::FloatGrid::Ptr readGrid(const std::string& path, const std::string& name) {
    hyvox::vdb::initializeOpenVdb();
    openvdb::io::File file(path);
    file.open();
    auto base = file.readGrid(name);
    file.close();
    return openvdb::gridPtrCast<openvdb::FloatGrid>(base);
}

// The density values set voxel by voxel through an accessor: slow and plain, the reference
// the library's leaf-by-leaf copy is checked against.
openvdb::FloatGrid::Ptr densityVoxelByVoxel(const hyvox::SparseGrid& occupancy) {
    auto grid = openvdb::FloatGrid::create(0.0f);
    auto accessor = grid->getAccessor();
    for (const auto& ijk : occupancy.coords()) accessor.setValueOn(openvdb::Coord(ijk[0], ijk[1], ijk[2]), 1.0f);
    return grid;
}

std::string slurp(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

}  // namespace

TEST(IoVdb, LeafCopyEqualsVoxelByVoxel) {
    for (double fill : {0.0, 0.02, 0.5, 1.0}) {
        const auto r = sampleResult(11, fill);
        const auto fast = hyvox::vdb::makeDensityGrid(r.grid, r.occupancy);
        const auto slow = densityVoxelByVoxel(r.occupancy);
        EXPECT_EQ(fast->activeVoxelCount(), r.occupancy.count()) << "fill " << fill;
        EXPECT_EQ(fast->tree().leafCount(), slow->tree().leafCount());
        EXPECT_EQ(activeCoords(*fast), activeCoords(*slow));
        // Every value, active or not, agrees (inactive ones are the background 0).
        for (auto leaf = slow->tree().cbeginLeaf(); leaf; ++leaf) {
            const auto* other = fast->tree().probeConstLeaf(leaf->origin());
            ASSERT_NE(other, nullptr);
            EXPECT_EQ(other->getValueMask(), leaf->getValueMask());
            for (openvdb::Index n = 0; n < 512; ++n) EXPECT_EQ(other->getValue(n), leaf->getValue(n));
        }
    }
}

TEST(IoVdb, LeafOriginsFollowBrickLayout) {
    hyvox::VoxelizeResult r = sampleResult(1, 0.0);  // only the two corner voxels
    r.occupancy.set(17, 9, 3);                       // brick (2,1,0)
    const auto grid = hyvox::vdb::makeDensityGrid(r.grid, r.occupancy);
    EXPECT_EQ(grid->tree().leafCount(), 3u);
    const auto* leaf = grid->tree().probeConstLeaf(openvdb::Coord(16, 8, 0));
    ASSERT_NE(leaf, nullptr);
    EXPECT_EQ(leaf->origin(), openvdb::Coord(16, 8, 0));
    EXPECT_EQ(leaf->onVoxelCount(), 1u);
    EXPECT_TRUE(leaf->isValueOn(openvdb::Coord(17, 9, 3)));
    EXPECT_EQ(leaf->getValue(openvdb::Coord(17, 9, 3)), 1.0f);
    EXPECT_TRUE(grid->tree().isValueOn(openvdb::Coord(36, 19, 8)));
}

TEST(IoVdb, RoundTripWorldCentres) {
    TempDir dir;
    const auto r = sampleResult();
    const std::string path = (dir.path / "out.vdb").string();
    hyvox::writeVdb(r, path);
    EXPECT_EQ(dir.names(), std::vector<std::string>{"out.vdb"});  // no temporary left behind

    const auto grid = readGrid(path, "density");
    ASSERT_TRUE(grid);
    EXPECT_EQ(grid->getGridClass(), openvdb::GRID_FOG_VOLUME);
    EXPECT_EQ(grid->background(), 0.0f);
    EXPECT_EQ(grid->metaValue<std::string>("hyvox_method"), "cpu");
    EXPECT_EQ(grid->metaValue<std::string>("hyvox_mode"), "conservative");
    EXPECT_DOUBLE_EQ(grid->metaValue<double>("hyvox_voxel_size"), 0.1);
    EXPECT_FALSE(grid->metaValue<std::string>("hyvox_version").empty());
    EXPECT_EQ(grid->metaValue<openvdb::Vec3i>("hyvox_dims"), openvdb::Vec3i(37, 20, 9));

    // World-space centres of the file's active voxels = the voxel set's centres.
    std::vector<std::array<double, 3>> from_file, expected;
    for (auto it = grid->cbeginValueOn(); it; ++it) {
        EXPECT_EQ(*it, 1.0f);
        const openvdb::Vec3d w = grid->indexToWorld(it.getCoord());
        from_file.push_back({w.x(), w.y(), w.z()});
    }
    for (const auto& ijk : r.occupancy.coords()) expected.push_back(r.grid.voxelCentre(ijk[0], ijk[1], ijk[2]));
    std::sort(from_file.begin(), from_file.end());
    std::sort(expected.begin(), expected.end());
    ASSERT_EQ(from_file.size(), expected.size());
    for (std::size_t n = 0; n < expected.size(); ++n)
        for (int a = 0; a < 3; ++a) EXPECT_NEAR(from_file[n][a], expected[n][a], 1e-12) << n;
    // Voxel (0,0,0)'s min corner is the grid origin.
    const openvdb::Vec3d corner = grid->indexToWorld(openvdb::Vec3d(-0.5, -0.5, -0.5));
    EXPECT_NEAR(corner.x(), -1.25, 1e-12);
    EXPECT_NEAR(corner.y(), 0.5, 1e-12);
    EXPECT_NEAR(corner.z(), 3.0, 1e-12);
}

TEST(IoVdb, CountGridWhenMultiValued) {
    TempDir dir;
    auto r = sampleResult();
    r.counts = {{0, 0, 0, 3}, {36, 19, 8, 1}, {5, 6, 7, 42}};
    const std::string path = (dir.path / "counts.vdb").string();
    hyvox::writeVdb(r, path);
    const auto count = readGrid(path, "count");
    ASSERT_TRUE(count);
    EXPECT_EQ(count->activeVoxelCount(), 3u);
    EXPECT_EQ(count->tree().getValue(openvdb::Coord(5, 6, 7)), 42.0f);
    EXPECT_EQ(count->tree().getValue(openvdb::Coord(0, 0, 0)), 3.0f);

    // Without counts there is no count grid.
    const std::string plain = (dir.path / "plain.vdb").string();
    hyvox::writeVdb(sampleResult(), plain);
    openvdb::io::File file(plain);
    file.open();
    EXPECT_TRUE(file.hasGrid("density"));
    EXPECT_FALSE(file.hasGrid("count"));
    file.close();
}

TEST(IoVdb, EmptyResultWritesAnEmptyGrid) {
    TempDir dir;
    const auto r = sampleResult(3, 0.0);
    hyvox::VoxelizeResult empty = r;
    empty.occupancy = hyvox::SparseGrid(r.grid.dims);
    const std::string path = (dir.path / "empty.vdb").string();
    hyvox::writeVdb(empty, path);
    EXPECT_EQ(readGrid(path, "density")->activeVoxelCount(), 0u);
}

TEST(IoVdb, OverwritesAnExistingFile) {
    TempDir dir;
    const fs::path path = dir.path / "out.vdb";
    std::ofstream(path) << "old";
    hyvox::writeVdb(sampleResult(), path.string());
    EXPECT_NE(slurp(path), "old");
    EXPECT_EQ(readGrid(path.string(), "density")->activeVoxelCount(), sampleResult().occupancy.count());
    EXPECT_EQ(dir.names(), std::vector<std::string>{"out.vdb"});
}

TEST(IoVdb, UnwritableFolderFailsWithoutAFile) {
    // /proc refuses new files even to root (tests may run as root, which ignores chmod).
    EXPECT_THROW(hyvox::writeVdb(sampleResult(), "/proc/hyvox-test-out.vdb"), hyvox::InvalidInput);
    EXPECT_FALSE(fs::exists("/proc/hyvox-test-out.vdb"));
    TempDir dir;
    EXPECT_THROW(hyvox::writeVdb(sampleResult(), (dir.path / "missing" / "out.vdb").string()), hyvox::InvalidInput);
    EXPECT_THROW(hyvox::writeVdb(sampleResult(), dir.path.string()), hyvox::InvalidInput);  // a folder
    EXPECT_TRUE(dir.names().empty());
    try {
        hyvox::writeVdb(sampleResult(), (dir.path / "missing" / "out.vdb").string());
        ADD_FAILURE() << "expected InvalidInput";  // else the message check below never runs
    } catch (const hyvox::InvalidInput& e) {
        EXPECT_NE(std::string(e.what()).find("missing"), std::string::npos) << e.what();
    }
}

TEST(IoVdb, FailedWriteKeepsTheExistingFile) {
    // A file-size limit makes the write fail halfway, like a full disk.
    TempDir dir;
    const fs::path path = dir.path / "keep.vdb";
    std::ofstream(path) << "previous contents";
    struct rlimit old {};
    ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &old), 0);
    auto previous_handler = std::signal(SIGXFSZ, SIG_IGN);  // get EFBIG instead of a signal
    struct rlimit small = old;
    small.rlim_cur = 2000;
    ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
    bool threw = false;
    try {
        hyvox::writeVdb(sampleResult(5, 0.5), path.string());
    } catch (const hyvox::ResourceError& e) {
        threw = true;
        EXPECT_NE(std::string(e.what()).find("keep.vdb"), std::string::npos) << e.what();
    }
    ::setrlimit(RLIMIT_FSIZE, &old);
    std::signal(SIGXFSZ, previous_handler);
    EXPECT_TRUE(threw);
    EXPECT_EQ(slurp(path), "previous contents");
    EXPECT_EQ(dir.names(), std::vector<std::string>{"keep.vdb"});  // the temporary is gone
}

TEST(IoVdb, AGridOverTheMemoryBudgetIsRefusedBeforeItIsBuilt) {
    TempDir dir;
    const hyvox::VoxelizeResult r = sampleResult(5, 1.0);  // 37x20x9 all set: 5x3x2 = 30 leaves, ~66 KB as floats
    hyvox::WriteOptions one_mib;
    one_mib.memory_budget_mib = 1;
    const std::uint64_t need = hyvox::vdb::densityGridBytes(r.occupancy);
    EXPECT_GT(need, 30u * 512u * sizeof(float));  // at least the leaves' values
    EXPECT_LT(need, 1u << 20);
    const std::string path = (dir.path / "fits.vdb").string();
    hyvox::writeVdb(r, path, one_mib);  // fits in 1 MiB
    EXPECT_TRUE(fs::exists(path));
    // A result of 15360 leaves does not: the writer lists each and serializes it (about 220
    // bytes) twice, about 6 MiB (io::vdbWriterBytes).
    hyvox::VoxelizeResult big;
    big.grid.dims = {8 * 32, 8 * 24, 8 * 20};
    big.occupancy = hyvox::SparseGrid(big.grid.dims);
    for (int bx = 0; bx < 32; ++bx)
        for (int by = 0; by < 24; ++by)
            for (int bz = 0; bz < 20; ++bz) big.occupancy.set(bx * 8, by * 8, bz * 8);
    EXPECT_GT(hyvox::vdb::vdbWriterBytes(15360, 0, 0, 0), double(1 << 20));
    const std::string refused = (dir.path / "refused.vdb").string();
    EXPECT_THROW(hyvox::writeVdb(big, refused, one_mib), hyvox::ResourceError);
    EXPECT_FALSE(fs::exists(refused));
    // The budget is the write's own: the voxelization's (in the result's stats) has no say.
    big.stats.options.memory_budget_mib = 1;
    hyvox::writeVdb(big, refused);
    EXPECT_TRUE(fs::exists(refused));
}

namespace {

// A result whose file is several MiB: random bits in 192^3 (the write checks every 256 KiB).
hyvox::VoxelizeResult largeResult() {
    hyvox::VoxelizeResult r;
    r.grid.origin = {0.0, 0.0, 0.0};
    r.grid.voxel_size = 1.0;
    r.grid.dims = {256, 256, 256};  // 32768 leaves: eight of the writer's batches
    r.occupancy = hyvox::SparseGrid(r.grid.dims);
    std::mt19937 rng(3);
    std::bernoulli_distribution on(0.1);
    for (int i = 0; i < 256; ++i)
        for (int j = 0; j < 256; ++j)
            for (int k = 0; k < 256; ++k)
                if (on(rng)) r.occupancy.set(i, j, k);
    r.stats.method = "cpu";
    r.stats.mode = "conservative";
    r.stats.voxel_count = r.occupancy.count();
    return r;
}

// Records the progress it sees; asks to stop once it passes stop_after (never: 101).
class ProgressRecorder final : public hyvox::Interrupter {
public:
    explicit ProgressRecorder(int stop_after) : stop_after_(stop_after) {}
    bool wasInterrupted(int percent) override {
        const std::lock_guard<std::mutex> lock(mutex_);
        seen.push_back(percent);
        return percent > stop_after_;
    }
    std::vector<int> seen;

private:
    int stop_after_;
    std::mutex mutex_;
};

}  // namespace

TEST(IoVdb, TheFileWriteReportsProgressAndCanBeCancelled) {
    const hyvox::VoxelizeResult result = largeResult();
    TempDir dir;
    const fs::path path = dir.path / "big.vdb";
    ProgressRecorder follow(101);
    hyvox::writeVdb(result, path.string(), {}, &follow);
    EXPECT_EQ(readGrid(path.string(), "density")->activeVoxelCount(), result.occupancy.count());
    // The batches going out are followed (progress 11-98: the first batch's end lies between),
    // and the end is 100.
    const auto between = std::find_if(follow.seen.begin(), follow.seen.end(), [](int p) { return p > 11 && p < 98; });
    ASSERT_NE(between, follow.seen.end());
    EXPECT_EQ(follow.seen.back(), 100);

    // Asked to stop after the first batch, half the file written: Cancelled, and the earlier
    // file stays as it was.
    const std::string before = slurp(path);
    ProgressRecorder stop(*between - 1);  // stops at *between
    EXPECT_THROW(hyvox::writeVdb(result, path.string(), {}, &stop), hyvox::Cancelled);
    EXPECT_EQ(stop.seen.back(), *between);
    EXPECT_TRUE(slurp(path) == before);                           // (not EXPECT_EQ: a mismatch would print megabytes)
    EXPECT_EQ(dir.names(), std::vector<std::string>{"big.vdb"});  // no temporary left
}
