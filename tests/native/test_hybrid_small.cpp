// SPDX-License-Identifier: GPL-3.0-or-later
// The GL methods on small hand-checked cases and their options: faces on voxel planes,
// sub-voxel triangles, clipping, tiles, the voxel list (section 3.5), the hybrid's two
// limits (cutoff 0 = fragment-parallel, huge = triangle-parallel), the auto cutoff, stats,
// and the clear errors (bad shader folder, no such device, grid too large).
#include <gtest/gtest.h>

#include <fstream>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <filesystem>

#include "hybrid/hybrid_run.h"
#include "hyvox/voxelize.h"
#include "support/mesh_arrays.h"
#include "support/temp_dir.h"
#include "support/test_mesh_loader.h"
#include "support/triangle_soup.h"
#include "support/voxel_checks.h"

namespace hyvox {
namespace {

constexpr Method kGlMethods[] = {Method::Triangle, Method::Fragment, Method::Hybrid};

VoxelizeOptions options(Method method, Mode mode = Mode::Conservative) {
    VoxelizeOptions o;
    o.method = method;
    o.mode = mode;
    o.hybrid.cutoff = 2.0;
    return o;
}

// options() on a grid of 8 unit voxels per axis over [0, 8]³ whatever the mesh.
VoxelizeOptions onUnitGrid(Method method, Mode mode = Mode::Conservative) {
    VoxelizeOptions o = options(method, mode);
    o.grid = test::unitGrid(8);
    return o;
}

// The hybrid section of a GL method's stats (every GL method's run has one).
const HybridStats& hybridStats(const VoxelizeResult& r) {
    if (!r.stats.hybrid) throw std::runtime_error("no hybrid stats in a GL method's result");
    return *r.stats.hybrid;
}

TEST(GlSmall, FaceOnVoxelPlaneMarksBothSides) {
    // A square in the plane z = 4 from (1,1) to (3,3): conservative marks columns x,y in
    // 0..3 (closed boxes touching the edges) on both sides, z = 3 and z = 4.
    test::TriangleSoup soup;
    soup.add({1, 1, 4}, {3, 1, 4}, {3, 3, 4});
    soup.add({1, 1, 4}, {3, 3, 4}, {1, 3, 4});
    for (Method method : kGlMethods) {
        SCOPED_TRACE(toString(method));
        const VoxelizeResult r = voxelize(soup.view(), onUnitGrid(method));
        EXPECT_EQ(r.occupancy.count(), 4u * 4u * 2u);
        for (int x = 0; x <= 3; ++x)
            for (int y = 0; y <= 3; ++y) {
                EXPECT_TRUE(r.occupancy.test(x, y, 3));
                EXPECT_TRUE(r.occupancy.test(x, y, 4));
            }
    }
}

TEST(GlSmall, BoxOnVoxelPlanesMatchesTheReferenceWithoutHoles) {
    // Architecture-style input: every face on a voxel plane, every edge on a voxel edge.
    test::TriangleSoup soup;
    soup.addBox({2, 1, 3}, {6, 7, 5});
    soup.addBox({0, 0, 0}, {8, 8, 8});
    for (Mode mode : {Mode::Conservative, Mode::Thin}) {
        VoxelizeOptions o = onUnitGrid(mode == Mode::Conservative ? Method::Reference : Method::Cpu, mode);
        const VoxelizeResult oracle = voxelize(soup.view(), o);
        for (Method method : kGlMethods) {
            SCOPED_TRACE(std::string(toString(method)) + " " + toString(mode));
            o.method = method;
            const VoxelizeResult r = voxelize(soup.view(), o);
            EXPECT_EQ(r.occupancy, oracle.occupancy);  // exact here: all coordinates are integers
            if (mode == Mode::Conservative) {
                std::uint64_t samples = 0;
                EXPECT_EQ(test::countHoles(soup.view(), r, &samples, nullptr), 0u);
                EXPECT_GT(samples, 100u);
            }
        }
    }
}

TEST(GlSmall, TinyTriangleInsideOneVoxelSetsOnlyIt) {
    test::TriangleSoup soup;
    soup.add({5.2, 2.3, 6.4}, {5.6, 2.4, 6.5}, {5.3, 2.7, 6.8});
    for (Mode mode : {Mode::Conservative, Mode::Thin})
        for (Method method : kGlMethods) {
            SCOPED_TRACE(std::string(toString(method)) + " " + toString(mode));
            const VoxelizeResult r = voxelize(soup.view(), onUnitGrid(method, mode));
            ASSERT_EQ(r.occupancy.count(), 1u);
            EXPECT_TRUE(r.occupancy.test(5, 2, 6));
        }
}

// Random triangles of every size and orientation, some far outside the grid (clipped).
test::TriangleSoup randomSoup(int count, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> pos(-2.0, 34.0), small(-1.5, 1.5);
    test::TriangleSoup soup;
    for (int t = 0; t < count; ++t) {
        const std::array<double, 3> a{pos(rng), pos(rng), pos(rng)};
        if (t % 3 == 0) {
            soup.add(a, {pos(rng), pos(rng), pos(rng)}, {pos(rng), pos(rng), pos(rng)});
        } else {
            soup.add(a, {a[0] + small(rng), a[1] + small(rng), a[2] + small(rng)},
                     {a[0] + small(rng), a[1] + small(rng), a[2] + small(rng)});
        }
    }
    return soup;
}

TEST(GlSmall, RandomTrianglesMatchOraclesWithClipping) {
    const test::TriangleSoup soup = randomSoup(300, 7);
    for (Mode mode : {Mode::Conservative, Mode::Thin}) {
        VoxelizeOptions o = options(mode == Mode::Conservative ? Method::Reference : Method::Cpu, mode);
        o.grid.voxel_size = 1.0;
        o.grid.bounds = Bounds{{0, 0, 0}, {32, 29, 31}};  // clips what lies outside
        const VoxelizeResult oracle = voxelize(soup.view(), o);
        for (Method method : kGlMethods) {
            SCOPED_TRACE(std::string(toString(method)) + " " + toString(mode));
            o.method = method;
            const VoxelizeResult r = voxelize(soup.view(), o);
            const auto cmp = test::compareResults(soup.view(), mode, r, oracle);
            EXPECT_TRUE(cmp.unexplained.empty()) << cmp.summary();
            EXPECT_GT(cmp.result_voxels, 1000u);
        }
    }
}

// Slivers: tiny projected area (small for the hybrid's pass 1) but long, so one compute
// invocation walks hundreds of columns (on llvmpipe, in chunks).
TEST(GlSmall, LongSliversMatchTheReference) {
    test::TriangleSoup soup;
    soup.add({1.0, 1.0, 1.0}, {250.5, 200.25, 120.0}, {1.5, 1.25, 1.0});
    soup.add({3.0, 250.0, 7.0}, {240.0, 2.0, 9.0}, {3.01, 250.0, 7.4});
    soup.add({0.0, 0.0, 0.0}, {255.0, 255.0, 255.0}, {0.0, 0.0, 0.5});
    VoxelizeOptions o = options(Method::Reference);
    o.grid.voxel_size = 1.0;
    o.grid.bounds = Bounds{{0, 0, 0}, {256, 256, 256}};
    o.hybrid.cutoff = 100.0;  // their projected areas are 30-64 voxel units²
    const VoxelizeResult oracle = voxelize(soup.view(), o);
    for (Method method : kGlMethods) {
        SCOPED_TRACE(toString(method));
        o.method = method;
        const VoxelizeResult r = voxelize(soup.view(), o);
        const auto cmp = test::compareResults(soup.view(), Mode::Conservative, r, oracle);
        EXPECT_TRUE(cmp.unexplained.empty()) << cmp.summary();
        if (method == Method::Hybrid) {
            EXPECT_EQ(hybridStats(r).large_triangles, 0u);
        }
    }
}

// Planeless needles (the fuzz finding of test_cpu_vs_reference.cpp, and one off the grid's
// diagonal): a far corner at ~-2.5e33 and two corners 1e-37 apart near the origin, which
// coincide in voxel space. Every GL method dropped them (a zero cross product: no dominant
// axis, a NaN depth range, nothing to rasterize). At 200 they cross several llvmpipe chunks.
TEST(GlSmall, PlanelessNeedlesMatchTheExactMethods) {
    test::TriangleSoup soup;
    const std::array<double, 3> near_a{-1.924353e-37, 1.1985432e-38, 0.0},
        near_b{-1.41794e-37, -1.917669e-37, -1.917669e-37};
    soup.add(near_b, near_a, {-2.5045195e+33, -2.5045195e+33, -2.5045195e+33});
    soup.add(near_b, near_a, {-2.5045195e+33, -1.1e+33, -0.4e+33});
    for (int resolution : {35, 200})
        for (Mode mode : {Mode::Conservative, Mode::Thin}) {
            VoxelizeOptions o = options(mode == Mode::Conservative ? Method::Reference : Method::Cpu, mode);
            o.grid.resolution = resolution;
            o.grid.padding = 1;
            const VoxelizeResult oracle = voxelize(soup.view(), o);
            EXPECT_GE(oracle.occupancy.count(), std::uint64_t(resolution));
            for (Method method : kGlMethods) {
                SCOPED_TRACE(std::string(toString(method)) + " " + toString(mode) + " " + std::to_string(resolution));
                o.method = method;
                const VoxelizeResult r = voxelize(soup.view(), o);
                // Touches are many here (the diagonal needle runs through voxel corners), and
                // float and double round them differently: only unexplained voxels count.
                const auto cmp = test::compareResults(soup.view(), mode, r, oracle);
                EXPECT_TRUE(cmp.unexplained.empty()) << cmp.summary();
                EXPECT_GE(cmp.result_voxels, std::uint64_t(resolution));
            }
        }
}

// Every GL method, in both modes, sets at least `min_voxels` and none that the exact method
// does not explain (the oracle as in the needle test above: the reference in conservative
// mode, cpu in thin mode).
void expectGlMethodsMatchTheExactMethods(const std::vector<float>& positions,
                                         const std::vector<std::uint32_t>& triangles, int resolution,
                                         std::size_t min_voxels) {
    const MeshView mesh = test::viewOf(positions, triangles);
    for (Mode mode : {Mode::Conservative, Mode::Thin}) {
        VoxelizeOptions o = options(mode == Mode::Conservative ? Method::Reference : Method::Cpu, mode);
        o.grid.resolution = resolution;
        const VoxelizeResult oracle = voxelize(mesh, o);
        for (Method method : kGlMethods) {
            SCOPED_TRACE(std::string(toString(method)) + " " + toString(mode));
            o.method = method;
            const VoxelizeResult r = voxelize(mesh, o);
            const auto cmp = test::compareResults(mesh, mode, r, oracle);
            EXPECT_TRUE(cmp.unexplained.empty()) << cmp.summary();
            EXPECT_GE(cmp.result_voxels, min_voxels);
        }
    }
}

// The sliver of CpuVsReference.ThinSliverNearTheOriginFromTheFuzzer: 35 voxels long, ~1e-19
// wide. The fragment method dropped it: the length of its short end underflowed in float,
// and the dilated triangle became NaN.
TEST(GlSmall, SliverWithAnEndTooShortForFloatMatchesTheExactMethods) {
    expectGlMethodsMatchTheExactMethods({0.0f, 4.9223826e-38f, -1.0652918e-37f,       //
                                         1.41499e-17f, 8.843688e-18f, 8.843688e-18f,  //
                                         -1.912195e-37f, -1.9029754e-37f, 0.0f},
                                        {0, 2, 1}, 35, 1);
}

// The sliver of CpuVsReference.SliverBesideADiagonalFromTheFuzzer: 2.5e-76 wide, passing
// 1.5e-5 voxel beside the x = z diagonal. The cpu method set the wrong side (its double
// normal lost the width); in float the GL methods see a segment (the width underflows) and
// set the right side. This keeps them there: one voxel per slab along x at least.
TEST(GlSmall, SliverBesideADiagonalMatchesTheExactMethods) {
    expectGlMethodsMatchTheExactMethods({-2.50451951e+33f, 2.11894795e-33f, -2.50448284e+33f,  //
                                         8.85928915e-41f, 0.0f, -1.91017832e-37f,              //
                                         -9.40395481e-38f, 2.1019477e-44f, 8.0f},
                                        {1, 0, 2}, 30, 30);
}

test::TestMesh bunny() { return test::loadTestMesh(test::meshPath("bunny_stanford_69k.ply")); }

TEST(GlSmall, HybridLimitsAreFragmentAndTriangleParallel) {
    const test::TestMesh mesh = bunny();
    VoxelizeOptions o = options(Method::Triangle);
    o.grid.resolution = 64;
    const VoxelizeResult triangle = voxelize(mesh.view(), o);
    o.method = Method::Fragment;
    const VoxelizeResult fragment = voxelize(mesh.view(), o);
    EXPECT_EQ(triangle.occupancy, fragment.occupancy);

    o.method = Method::Hybrid;
    o.hybrid.cutoff = 0.0;  // everything is large: all rasterized in pass 2
    const VoxelizeResult all_large = voxelize(mesh.view(), o);
    EXPECT_EQ(all_large.occupancy, fragment.occupancy);
    EXPECT_EQ(hybridStats(all_large).large_triangles, all_large.stats.triangles_used);

    o.hybrid.cutoff = 1e30;  // nothing is large: all voxelized in pass 1
    const VoxelizeResult all_small = voxelize(mesh.view(), o);
    EXPECT_EQ(all_small.occupancy, triangle.occupancy);
    EXPECT_EQ(hybridStats(all_small).large_triangles, 0u);

    o.hybrid.cutoff = 0.5;  // a mix
    const VoxelizeResult mixed = voxelize(mesh.view(), o);
    EXPECT_EQ(mixed.occupancy, triangle.occupancy);
    EXPECT_GT(hybridStats(mixed).large_triangles, 0u);
    EXPECT_LT(hybridStats(mixed).large_triangles, mixed.stats.triangles_used);
}

TEST(GlSmall, AutoCutoffSearchesOnceThenUsesTheCache) {
    const test::TestMesh mesh = test::loadTestMesh(test::meshPath("teapot_utah.ply"));
    VoxelizeOptions o = options(Method::Hybrid);
    o.grid.resolution = 48;
    o.hybrid.cutoff = -1.0;
    const VoxelizeResult first = voxelize(mesh.view(), o);
    EXPECT_GT(hybridStats(first).cutoff_search_runs, 2u);
    EXPECT_GT(hybridStats(first).cutoff, 0.0);
    const VoxelizeResult second = voxelize(mesh.view(), o);
    EXPECT_EQ(hybridStats(second).cutoff_search_runs, 0u);
    EXPECT_EQ(hybridStats(second).cutoff, hybridStats(first).cutoff);
    o.method = Method::Triangle;
    EXPECT_EQ(first.occupancy, voxelize(mesh.view(), o).occupancy);
}

TEST(GlSmall, StatsReportPassesAndTransfers) {
    const test::TestMesh mesh = bunny();
    VoxelizeOptions o = options(Method::Hybrid);
    o.grid.resolution = 64;
    const VoxelizeResult r = voxelize(mesh.view(), o);
    // The hybrid section and no other backend's.
    ASSERT_TRUE(r.stats.hybrid.has_value());
    EXPECT_FALSE(r.stats.cpu || r.stats.reference || r.stats.tessellation);
    EXPECT_GT(r.stats.hybrid->pass1_gpu_ms, 0.0);
    EXPECT_EQ(r.stats.hybrid->cutoff, 2.0);  // the options' cutoff, reported
    EXPECT_EQ(r.stats.voxel_count, r.occupancy.count());
}

TEST(GlSmall, TilesGiveTheSameVoxels) {
    const test::TestMesh mesh = bunny();
    VoxelizeOptions o = options(Method::Hybrid);
    o.grid.resolution = 96;
    for (Method method : kGlMethods) {
        SCOPED_TRACE(toString(method));
        o.method = method;
        o.gl.tile_bytes = 0;
        const VoxelizeResult whole = voxelize(mesh.view(), o);
        EXPECT_EQ(hybridStats(whole).tiles, 1u);
        // One slab of 8 voxels at 96 voxels is 12 x 12 bricks of 64 bytes: 9216 bytes.
        o.gl.tile_bytes = 3 * 9216;
        const VoxelizeResult tiled = voxelize(mesh.view(), o);
        EXPECT_GE(hybridStats(tiled).tiles, 3u);
        EXPECT_EQ(tiled.occupancy, whole.occupancy);
    }
}

TEST(GlSmall, VoxelListHoldsEachSetVoxelOnce) {
    const test::TestMesh mesh = bunny();
    for (Method method : kGlMethods) {
        SCOPED_TRACE(toString(method));
        VoxelizeOptions o = options(method);
        o.grid.resolution = 80;
        const VoxelizeResult bits = voxelize(mesh.view(), o);
        // Through the backend entry point that also serves voxelize().
        const ValidatedMesh validated = validate(mesh.view());
        const GridSpec grid = makeGrid(validated.bounds, o.grid);
        o.gl.tile_bytes = 4 * 10 * 10 * 64;  // several tiles too
        const Tile whole{{0, 0, 0}, grid.dims};
        const BackendJob job{validated, validated, grid, whole, o, nullptr, nullptr};
        std::vector<std::array<std::int32_t, 3>> list;
        hybrid::runHybrid(job, nullptr, &list);
        std::sort(list.begin(), list.end());
        auto expected = bits.occupancy.coords();
        std::sort(expected.begin(), expected.end());
        EXPECT_EQ(list, expected);
    }
}

TEST(GlSmall, GridTooLargeForOneSlabIsRefusedClearly) {
    // A gl_tile_bytes below one slab is the option's fault: named, with the bytes one slab
    // needs (it used to read "needs 0 MiB per slab, more than the limit of 0 MiB").
    const test::TestMesh mesh = bunny();
    VoxelizeOptions o = options(Method::Triangle);
    o.grid.resolution = 512;
    o.gl.tile_bytes = 4096;
    const GridSpec grid = makeGrid(validate(mesh.view()).bounds, o.grid);
    const std::uint64_t slab_bytes = std::uint64_t((grid.dims[1] + 7) / 8) * std::uint64_t((grid.dims[2] + 7) / 8) * 64;
    try {
        voxelize(mesh.view(), o);
        FAIL() << "expected InvalidInput";
    } catch (const InvalidInput& e) {
        EXPECT_EQ(std::string(e.what()),
                  "gl_tile_bytes 4096 is less than one 8-voxel slab of this " + grid.dimsText() + " grid (" +
                      std::to_string(slab_bytes) + " bytes); give at least that");
    }
    o.gl.tile_bytes = slab_bytes;  // exactly one slab per tile: runs
    EXPECT_GT(voxelize(mesh.view(), o).occupancy.count(), 0u);
}

TEST(GlSmall, MissingShaderFolderIsAClearError) {
    test::TriangleSoup soup;
    soup.add({0, 0, 0}, {1, 0, 0}, {0, 1, 1});
    VoxelizeOptions o = options(Method::Triangle);
    o.grid.resolution = 8;
    o.gl.shader_dir = "/nonexistent/hyvox-shaders";
    try {
        voxelize(soup.view(), o);
        FAIL() << "expected BackendError";
    } catch (const BackendError& e) {
        EXPECT_NE(std::string(e.what()).find("/nonexistent/hyvox-shaders/hybrid/triangle_parallel.comp"),
                  std::string::npos)
            << e.what();
    }
}

TEST(GlSmall, ShaderFolderFromTheOptionsIsUsed) {
    // A copy of shaders/ with a syntax error in one shared file: the error names the file
    // and quotes the driver's log.
    const test::TempDir temp;
    const std::filesystem::path dir = temp.path / "shaders";
    std::filesystem::copy(HYVOX_SOURCE_SHADERS, dir, std::filesystem::copy_options::recursive);
    std::ofstream(dir / "common" / "overlap.glsl", std::ios::app) << "\nthis is not glsl;\n";
    test::TriangleSoup soup;
    soup.add({0, 0, 0}, {1, 0, 0}, {0, 1, 1});
    VoxelizeOptions o = options(Method::Fragment);
    o.grid.resolution = 8;
    o.gl.shader_dir = dir.string();
    try {
        voxelize(soup.view(), o);
        FAIL() << "expected BackendError";
    } catch (const BackendError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("fragment_parallel"), std::string::npos) << what;
        EXPECT_NE(what.find("common/overlap.glsl"), std::string::npos) << what;
        EXPECT_NE(what.find("error"), std::string::npos) << what;
    }
    // And the unbroken copy on disk gives the embedded result.
    o.gl.shader_dir = HYVOX_SOURCE_SHADERS;
    const SparseGrid from_disk = voxelize(soup.view(), o).occupancy;
    o.gl.shader_dir = "";
    EXPECT_EQ(from_disk, voxelize(soup.view(), o).occupancy);
}

TEST(GlSmall, CancellationStopsAndTheWorkerCarriesOn) {
    struct StopAtOnce : Interrupter {
        bool wasInterrupted(int) override { return true; }
    } stop;
    const test::TestMesh mesh = bunny();
    VoxelizeOptions o = options(Method::Hybrid);
    o.grid.resolution = 32;
    EXPECT_THROW(voxelize(mesh.view(), o, &stop), Cancelled);
    EXPECT_GT(voxelize(mesh.view(), o).occupancy.count(), 0u);
}

TEST(GlSmall, NoSuchDeviceNamesTheDevicesFound) {
    test::TriangleSoup soup;
    soup.add({0, 0, 0}, {1, 0, 0}, {0, 1, 1});
    VoxelizeOptions o = options(Method::Triangle);
    o.grid.resolution = 8;
    o.gl.device = "99";
    try {
        voxelize(soup.view(), o);
        FAIL() << "expected BackendError";
    } catch (const BackendError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("'99'"), std::string::npos) << what;
        EXPECT_NE(what.find("software"), std::string::npos) << what;  // llvmpipe is always listed
    }
    o.gl.device = "software";
    EXPECT_GT(voxelize(soup.view(), o).occupancy.count(), 0u);
}

}  // namespace
}  // namespace hyvox
