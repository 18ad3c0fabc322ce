// SPDX-License-Identifier: GPL-3.0-or-later
// Cancellation and threads: an Interrupter that says stop makes voxelize throw
// hyvox::Cancelled (before or in the middle of the work), start/end are called once each,
// and the thread count does not change the result.
#include <gtest/gtest.h>

#include <atomic>

#include <tbb/task_arena.h>

#include "support/test_mesh_loader.h"
#include "support/triangle_soup.h"

namespace hyvox::test {
namespace {

class CountingInterrupter : public Interrupter {
public:
    explicit CountingInterrupter(int stop_after) : stop_after_(stop_after) {}
    void start(const char*) override { ++starts; }
    void end() override { ++ends; }
    bool wasInterrupted(int) override { return ++calls > stop_after_; }
    std::atomic<int> calls{0}, starts{0}, ends{0};

private:
    int stop_after_;
};

TEST(Cancellation, AlwaysInterruptedThrowsCancelled) {
    TriangleSoup box;
    box.addBox({0, 0, 0}, {1, 2, 3});
    for (Method method : {Method::Cpu, Method::Reference}) {
        VoxelizeOptions options;
        options.method = method;
        options.grid.resolution = 64;
        CountingInterrupter stop(0);
        EXPECT_THROW(voxelize(box.view(), options, &stop), Cancelled) << toString(method);
        EXPECT_EQ(stop.starts.load(), 1);
        EXPECT_EQ(stop.ends.load(), 1);
    }
}

TEST(Cancellation, InterruptedMidwayThrowsCancelled) {
    const TestMesh dragon = loadTestMesh(meshPath("dragon_stanford_871k.ply.gz"));
    for (Method method : {Method::Cpu, Method::Reference}) {
        VoxelizeOptions options;
        options.method = method;
        options.grid.resolution = 128;
        // Let the dispatcher's first check and a few of the backend's chunk checks pass.
        CountingInterrupter stop(5);
        EXPECT_THROW(voxelize(dragon.view(), options, &stop), Cancelled) << toString(method);
        EXPECT_GT(stop.calls.load(), 5);
        // Never interrupted: the same run completes and checked in between chunks.
        CountingInterrupter never(1 << 30);
        const VoxelizeResult result = voxelize(dragon.view(), options, &never);
        EXPECT_GT(result.stats.voxel_count, 0u);
        EXPECT_GT(never.calls.load(), 10) << "the backend should check the interrupter between chunks";
    }
}

// The checks before any progress (a million triangles validated and binned to tiles) also
// stop: a stop asked at the validation's first check ends the run there, with no tile done;
// one asked at the binning's first check likewise (small tiles force the binning). Chunks
// are checked in parallel: each thread may have begun one chunk (and asked once) before the
// stop reaches it, so "there" is up to one check per thread, never a chunk after.
TEST(Cancellation, ValidationAndBinningStopWhenAsked) {
    const TestMesh dragon = loadTestMesh(meshPath("dragon_stanford_871k.ply.gz"));
    const std::size_t checks = (dragon.view().triangle_count + kInterruptCheckTriangles - 1) / kInterruptCheckTriangles;
    constexpr int threads = 2;  // so at most 2 checks may happen, on any machine
    tbb::task_arena arena(threads);
    CountingInterrupter at_validation(0);
    arena.execute([&] { EXPECT_THROW(validate(dragon.view(), &at_validation), Cancelled); });
    EXPECT_GE(at_validation.calls.load(), 1);
    EXPECT_LE(at_validation.calls.load(), threads);
    CountingInterrupter never(1 << 30);
    const ValidatedMesh validated = validate(dragon.view(), &never);
    EXPECT_EQ(std::size_t(never.calls.load()), checks);

    VoxelizeOptions options;
    options.method = Method::Cpu;
    options.grid.resolution = 256;
    options.tile_size = 64;
    options.threads = threads;
    // Validation's checks pass, the dispatcher's 0% check passes, the binning's first stops.
    CountingInterrupter at_binning(int(checks) + 1);
    VoxelizeResult partial;
    EXPECT_THROW(partial = voxelize(dragon.view(), options, &at_binning), Cancelled);
    EXPECT_GE(std::size_t(at_binning.calls.load()), checks + 2);
    EXPECT_LE(std::size_t(at_binning.calls.load()), checks + 1 + std::size_t(threads));
}

TEST(Threads, ResultDoesNotDependOnTheThreadCount) {
    const TestMesh sponza = loadTestMesh(meshPath("sponza_crytek_262k_vcolor.ply.gz"));
    for (Mode mode : {Mode::Conservative, Mode::Thin}) {
        VoxelizeOptions options;
        options.grid.resolution = 200;
        options.mode = mode;
        options.threads = 1;
        const VoxelizeResult one = voxelize(sponza.view(), options);
        options.threads = 0;
        const VoxelizeResult all = voxelize(sponza.view(), options);
        options.threads = 3;
        const VoxelizeResult three = voxelize(sponza.view(), options);
        EXPECT_TRUE(one.occupancy == all.occupancy);
        EXPECT_TRUE(one.occupancy == three.occupancy);
        EXPECT_GT(one.stats.voxel_count, 0u);
    }
}

}  // namespace
}  // namespace hyvox::test
