// SPDX-License-Identifier: GPL-3.0-or-later
// The sdf attribute (hyvox/level_set.h) against independent oracles: every voxel's distance
// against a brute-force closest point in double (Ericson's, or the edges' for a triangle
// without area, over every triangle), the band
// complete (a voxel is active exactly when that distance is below the band); the signs against
// the same run's solid occupancy and the exact winding number (every triangle's solid angle
// summed) on the surface's own voxels; the .vdb grid accepted by OpenVDB's level-set tools
// (checkLevelSet, volumeToMesh: watertight, on the source surface); and on an open mesh the
// voxels OpenVDB's own meshToLevelSet signs wrong (its flood fill leaks through the holes)
// counted, hyvox's sign right on them.
#include <gtest/gtest.h>
#include <openvdb/tools/Diagnostics.h>
#include <openvdb/tools/MeshToVolume.h>
#include <openvdb/tools/VolumeToMesh.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "hyvox/errors.h"
#include "hyvox/hyvox.h"
#include "hyvox/vdb.h"
#include "sdf/band_bins.h"
#include "sdf/band_distances.h"
#include "solid/fast_winding.h"
#include "support/closest_point.h"
#include "support/temp_dir.h"
#include "support/test_mesh_loader.h"
#include "support/triangle_soup.h"
#include "vdb/vdb_grid.h"

namespace hyvox {
namespace {

using Vec3 = std::array<double, 3>;

using test::closest_point::pointTriangleDistance;

// The usable triangles in voxel space, with each one's box, for brute-force distances and
// exact winding numbers at voxel centres.
struct Oracle {
    Oracle(const ValidatedMesh& mesh, const GridSpec& grid) {
        for (const std::uint32_t t : mesh.usable) {
            std::array<Vec3, 3> c{grid.toVoxel(mesh.vertex(t, 0)), grid.toVoxel(mesh.vertex(t, 1)),
                                  grid.toVoxel(mesh.vertex(t, 2))};
            corners.push_back(c);
            Vec3 lo, hi;
            for (int a = 0; a < 3; ++a) {
                lo[a] = std::min({c[0][a], c[1][a], c[2][a]});
                hi[a] = std::max({c[0][a], c[1][a], c[2][a]});
            }
            boxes.push_back({lo, hi});
        }
    }
    // The distance (voxels) from voxel (i, j, k)'s centre to the mesh, or `cap` when it is
    // farther than that.
    double distance(int i, int j, int k, double cap) const { return distanceFrom({i + 0.5, j + 0.5, k + 0.5}, cap); }
    double distanceFrom(const Vec3& p, double cap) const {
        double best = cap;
        for (std::size_t t = 0; t < corners.size(); ++t) {
            double gap2 = 0;  // to the triangle's box: a lower bound
            for (int a = 0; a < 3; ++a) {
                const double d = std::max({boxes[t][0][a] - p[a], 0.0, p[a] - boxes[t][1][a]});
                gap2 += d * d;
            }
            if (gap2 >= best * best) continue;
            best = std::min(best, pointTriangleDistance(p, corners[t][0], corners[t][1], corners[t][2]));
        }
        return best;
    }
    double winding(int i, int j, int k) const {
        const Vec3 p{i + 0.5, j + 0.5, k + 0.5};
        double sum = 0;
        for (const auto& c : corners) sum += solid::triangleWinding(c[0], c[1], c[2], p);
        return sum;
    }
    std::vector<std::array<Vec3, 3>> corners;
    std::vector<std::array<Vec3, 2>> boxes;
};

// Every voxel of the level set: active or not, its value (the distance, or ±background), and
// whether its centre is inside. `at(i, j, k)` of voxels without a leaf: inside tile or outside.
struct LevelSetVoxels {
    explicit LevelSetVoxels(const VoxelizeResult& r) : result(r), bricks(r.grid.bricks()) {
        for (std::size_t n = 0; n < r.sdf.leaves.size(); ++n) leaf_of[r.sdf.leaves[n].brick] = n;
    }
    struct Voxel {
        bool active, inside;
        float value;
    };
    Voxel at(int i, int j, int k) const {
        const std::uint64_t brick = bricks.indexOfVoxel(i, j, k);
        const auto found = leaf_of.find(brick);
        const float bg = result.sdf.background;
        if (found == leaf_of.end()) {
            for (const SparseGrid::TileRun& run : result.sdf.inside_runs)
                if (brick >= run.begin && brick < run.end) return {false, true, -bg};
            return {false, false, bg};
        }
        const LevelSetGrid::Leaf& leaf = result.sdf.leaves[found->second];
        const int v = (i & 7) * 64 + (j & 7) * 8 + (k & 7);
        const bool active = (leaf.active[v >> 6] >> (v & 63)) & 1, inside = (leaf.inside[v >> 6] >> (v & 63)) & 1;
        if (!active) return {false, inside, inside ? -bg : bg};
        std::size_t index = leaf.first;
        for (int n = 0; n < v; ++n) index += (leaf.active[n >> 6] >> (n & 63)) & 1;
        return {true, inside, result.sdf.values[index]};
    }
    const VoxelizeResult& result;
    BrickLayout bricks;
    std::map<std::uint64_t, std::size_t> leaf_of;
};

VoxelizeOptions sdfOptions(int resolution, Mode mode = Mode::Solid, int band = 3) {
    VoxelizeOptions options;
    options.grid.resolution = resolution;
    options.mode = mode;
    options.attributes.sdf = true;
    options.sdf.band = band;
    return options;
}

// Every voxel of the grid: active exactly where the brute-force distance is below the band
// (voxels within 1e-9 of its edge either way), each active one's |value| that distance within
// 1e-5 voxel, each inactive one ±background.
void expectExactBand(const test::TriangleSoup& soup, const VoxelizeOptions& options, const char* what) {
    SCOPED_TRACE(what);
    const ValidatedMesh validated = validate(soup.view());
    const VoxelizeResult r = voxelize(soup.view(), options);
    const Oracle oracle(validated, r.grid);
    const LevelSetVoxels voxels(r);
    const double s = r.grid.voxel_size, band = options.sdf.band;
    EXPECT_FLOAT_EQ(r.sdf.background, float(band * s));
    std::uint64_t active = 0, worst_at = 0;
    double worst = 0;
    for (int i = 0; i < r.grid.dims[0]; ++i)
        for (int j = 0; j < r.grid.dims[1]; ++j)
            for (int k = 0; k < r.grid.dims[2]; ++k) {
                const double d = oracle.distance(i, j, k, band + 1.0);
                const LevelSetVoxels::Voxel v = voxels.at(i, j, k);
                if (std::fabs(d - band) < 1e-9) continue;
                ASSERT_EQ(v.active, d < band) << i << "," << j << "," << k << " at " << d << " voxels";
                if (!v.active) {
                    ASSERT_EQ(std::fabs(v.value), r.sdf.background);
                    continue;
                }
                ++active;
                const double error = std::fabs(std::fabs(double(v.value)) / s - d);
                if (error > worst) worst = error, worst_at = active;
            }
    EXPECT_LT(worst, 1e-5) << "at active voxel " << worst_at;
    EXPECT_EQ(active, r.sdf.activeCount());
    EXPECT_GT(active, 200u);
}

test::TriangleSoup soupOf(const test::TestMesh& mesh) {
    test::TriangleSoup soup;
    soup.positions = mesh.positions;
    soup.triangles = mesh.triangles;
    return soup;
}

TEST(SdfDistances, EveryVoxelMatchesTheBruteForceDistance) {
    // Closed (Spot), open with holes (the elephant), separate open patches (the teapot),
    // degenerate triangles and interpenetrating parts (the spider).
    for (const char* name : {"spot_vcolor.ply", "elephant_holes.ply", "teapot_utah.ply", "spider_messy.ply"})
        expectExactBand(soupOf(test::loadTestMesh(test::meshPath(name))), sdfOptions(24), name);
}

TEST(SdfDistances, FacesOnVoxelPlanesAndCentresSlivers) {
    // A box whose faces lie on voxel planes and through voxel centres (CAD), slivers 1e-7
    // voxel wide, a needle along a diagonal and a triangle that is a point: the cases a
    // frame or a normal could lose.
    test::TriangleSoup soup;
    soup.addBox({2.0, 2.5, 3.0}, {9.0, 7.5, 11.0});
    soup.add({3.0, 12.0, 2.0}, {11.0, 12.0000001, 9.0}, {7.0, 12.00000005, 5.5});
    soup.add({1.0, 1.0, 13.0}, {12.0, 13.0, 13.5}, {12.0, 13.0, 13.5000001});
    soup.add({14.0, 2.0, 2.0}, {14.0, 2.0, 2.0}, {14.0, 2.0, 2.0000001});
    VoxelizeOptions options = sdfOptions(1, Mode::Conservative, 2);
    options.grid.voxel_size = 1.0;
    expectExactBand(soup, options, "box, slivers, needle");
    options.sdf.band = 5;
    expectExactBand(soup, options, "a wider band");
}

TEST(SdfDistances, BoundsThatCutTheMeshKeepTheBandInTheGrid) {
    // Bounds below the mesh's top: triangles reach past the grid's end, where the band's rows
    // are computed in whole quads; every active voxel lies in the grid and matches the brute
    // force over the whole mesh. The cuts take the grid's depth through every remainder of 4.
    const test::TriangleSoup soup = soupOf(test::loadTestMesh(test::meshPath("spot_vcolor.ply")));
    const Bounds box = validate(soup.view()).bounds;
    for (int cut = 0; cut < 4; ++cut) {
        VoxelizeOptions options = sdfOptions(1, Mode::Conservative);
        const double voxel = (box.max[1] - box.min[1]) / 40.0;
        options.grid.voxel_size = voxel;
        Bounds bounds = box;
        bounds.max[2] = box.min[2] + (17.0 + cut) * voxel;
        options.grid.bounds = bounds;
        expectExactBand(soup, options, ("cut after " + std::to_string(17 + cut) + " voxels").c_str());
    }
}

// Every block of the band computed both ways, its small triangles swept and (wherever it has
// any) queried (sdf/band_queries.h), against the brute-force distance at every voxel of the
// grid: below the band, within 1e-5 voxel; beyond it, band² exactly. Counts the blocks
// queried into `queried_blocks`.
void expectBlocksMatchTheBruteForce(const test::TriangleSoup& soup, const VoxelizeOptions& options, const char* what,
                                    int& queried_blocks) {
    SCOPED_TRACE(what);
    const ValidatedMesh validated = validate(soup.view());
    VoxelizeOptions surface = options;
    surface.attributes = {};
    const GridSpec grid = voxelize(soup.view(), surface).grid;
    const Oracle oracle(validated, grid);
    const double band = options.sdf.band;
    const sdf::BandBins bins = sdf::binBand(validated, grid, band, std::uint64_t(1) << 32, 4096, nullptr);
    const sdf::BlockLayout blocks(grid);
    std::vector<double> swept(sdf::kBlockVoxels), queried(sdf::kBlockVoxels);
    sdf::BlockQueries queries;
    queried_blocks = 0;
    for (std::size_t number = 0; number < bins.blocks.size(); ++number) {
        std::uint64_t evaluations = 0;
        sdf::blockDistances(validated, grid, band, bins, number, swept.data(), evaluations, nullptr);
        sdf::blockDistances(validated, grid, band, bins, number, queried.data(), evaluations, &queries, 0.0);
        queried_blocks += queries.taken() > 0;
        const std::array<std::int32_t, 3> block = blocks.at(bins.blocks[number]);
        constexpr int kSide = sdf::BlockLayout::kSide;
        for (int x = 0; x < kSide; ++x)
            for (int y = 0; y < kSide; ++y)
                for (int z = 0; z < kSide; ++z) {
                    const int i = kSide * block[0] + x, j = kSide * block[1] + y, k = kSide * block[2] + z;
                    if (i >= grid.dims[0] || j >= grid.dims[1] || k >= grid.dims[2]) continue;
                    const double d = oracle.distance(i, j, k, band + 1.0);
                    if (std::fabs(d - band) < 1e-9) continue;
                    for (const double d2 : {swept[std::size_t(sdf::blockOffset(x, y, z))],
                                            queried[std::size_t(sdf::blockOffset(x, y, z))]}) {
                        if (d > band)
                            ASSERT_EQ(d2, band * band) << i << "," << j << "," << k;
                        else
                            ASSERT_NEAR(std::sqrt(d2), d, 1e-5) << i << "," << j << "," << k;
                    }
                }
    }
}

TEST(SdfDistances, QueriedAndSweptBlocksMatchTheBruteForceDistance) {
    // Spot at 24 and the spider at 16: triangles smaller than a voxel, bands of 2, 3 and 5.
    for (const int band : {2, 3, 5}) {
        for (const auto& [name, resolution] : {std::pair{"spot_vcolor.ply", 24}, std::pair{"spider_messy.ply", 16}}) {
            const std::string what = std::string(name) + ", band " + std::to_string(band);
            int queried_blocks = 0;
            expectBlocksMatchTheBruteForce(soupOf(test::loadTestMesh(test::meshPath(name))),
                                           sdfOptions(resolution, Mode::Conservative, band), what.c_str(),
                                           queried_blocks);
            EXPECT_GT(queried_blocks, 0) << what;
        }
    }
    // Slivers, a needle and a triangle that is a point (queried: the only small one) beside
    // a box's faces on voxel planes and through voxel centres.
    test::TriangleSoup soup;
    soup.addBox({2.0, 2.5, 3.0}, {9.0, 7.5, 11.0});
    soup.add({3.0, 12.0, 2.0}, {11.0, 12.0000001, 9.0}, {7.0, 12.00000005, 5.5});
    soup.add({1.0, 1.0, 13.0}, {12.0, 13.0, 13.5}, {12.0, 13.0, 13.5000001});
    soup.add({14.0, 2.0, 2.0}, {14.0, 2.0, 2.0}, {14.0, 2.0, 2.0000001});
    soup.add({5.3, 9.1, 4.2}, {5.9, 9.4, 4.25}, {5.5, 9.8, 4.9});
    VoxelizeOptions options = sdfOptions(1, Mode::Conservative, 3);
    options.grid.voxel_size = 1.0;
    int queried_blocks = 0;
    expectBlocksMatchTheBruteForce(soup, options, "box, slivers, needle, point", queried_blocks);
    EXPECT_GT(queried_blocks, 0);
}

TEST(SdfBins, EveryBlockWithinTheBandOfATriangleListsItInOrder) {
    // Small triangles scattered over grids of 64 blocks (one pass of the bins' radix sort)
    // and of 32 x 64 x 64 blocks (two passes: more than 65536). Each block's list holds
    // exactly the triangles whose box, grown by the band along each axis, holds one of its
    // voxel centres (brute force over the blocks; a triangle reaching at most 8 blocks is
    // binned into all of them without a distance test), ascending; the blocks ascend.
    for (const std::array<std::int32_t, 3> dims :
         {std::array<std::int32_t, 3>{128, 128, 128}, std::array<std::int32_t, 3>{1024, 2048, 2048}}) {
        SCOPED_TRACE(std::to_string(dims[0]) + "x" + std::to_string(dims[1]) + "x" + std::to_string(dims[2]));
        GridSpec grid;
        grid.dims = dims;
        std::mt19937 random(7);
        test::TriangleSoup soup;
        for (int n = 0; n < 400; ++n) {
            Vec3 corner;
            for (int a = 0; a < 3; ++a)
                corner[std::size_t(a)] =
                    std::uniform_real_distribution<double>(0, double(dims[std::size_t(a)]))(random);
            auto near = [&] {
                Vec3 c = corner;
                for (double& x : c) x += std::uniform_real_distribution<double>(-1.5, 1.5)(random);
                return c;
            };
            soup.add(corner, near(), near());
        }
        const ValidatedMesh validated = validate(soup.view());
        const double band = 3;
        const sdf::BandBins bins = sdf::binBand(validated, grid, band, std::uint64_t(1) << 32, 4096, nullptr);
        const sdf::BlockLayout blocks(grid);
        std::map<std::uint64_t, std::vector<std::uint32_t>> expected;
        constexpr int kSide = sdf::BlockLayout::kSide;
        for (const std::uint32_t t : validated.usable) {
            const auto corners = sdf::voxelCorners(validated, grid, t);
            // Along each axis, the blocks holding a voxel centre within the band of the box.
            std::array<std::vector<std::int32_t>, 3> near;
            for (int a = 0; a < 3; ++a) {
                const double lo = std::min({corners[0][a], corners[1][a], corners[2][a]});
                const double hi = std::max({corners[0][a], corners[1][a], corners[2][a]});
                for (int b = 0; b < blocks.counts[std::size_t(a)]; ++b) {
                    double least = HUGE_VAL;
                    for (int i = kSide * b; i < std::min(kSide * b + kSide, dims[std::size_t(a)]); ++i)
                        least = std::min(least, std::max({lo - (i + 0.5), 0.0, i + 0.5 - hi}));
                    if (least <= band) near[std::size_t(a)].push_back(b);
                }
            }
            for (std::size_t i = 0; i < near[0].size(); ++i)
                for (std::size_t j = 0; j < near[1].size(); ++j)
                    for (std::size_t k = 0; k < near[2].size(); ++k)
                        expected[blocks.index(near[0][i], near[1][j], near[2][k])].push_back(t);
        }
        ASSERT_EQ(bins.blocks.size(), expected.size());
        ASSERT_EQ(bins.start.size(), bins.blocks.size() + 1);
        std::size_t number = 0;
        for (const auto& [block, triangles] : expected) {
            ASSERT_EQ(bins.blocks[number], block) << number;
            const std::vector<std::uint32_t> listed(bins.triangles.begin() + long(bins.start[number]),
                                                    bins.triangles.begin() + long(bins.start[number + 1]));
            ASSERT_EQ(listed, triangles) << "block " << block;
            ++number;
        }
        if (dims[0] > 128) {
            EXPECT_GT(std::uint64_t(blocks.counts[0]) * blocks.counts[1] * blocks.counts[2], 65536u);
        }
        // A budget below what the pairs take: refused, naming it.
        const std::uint64_t pairs = bins.triangles.size();
        try {
            sdf::binBand(validated, grid, band, pairs * 8, 1, nullptr);
            ADD_FAILURE() << "bins over the budget were made";
        } catch (const ResourceError& e) {
            EXPECT_NE(std::string(e.what()).find("(triangle, block) pairs"), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find("memory budget of 1 MiB"), std::string::npos) << e.what();
        }
    }
}

// The signs: off the conservative surface, the solid run's own occupancy; on it, the exact
// winding number at the centre (>= 0.5 inside), where that is not within `margin` of 0.5 (the
// fast winding numbers' accuracy on open meshes) nor the centre within 1e-3 voxel of the mesh.
void expectSignsOfTheInsideTest(const char* name, int resolution, double margin) {
    SCOPED_TRACE(name);
    const test::TestMesh mesh = test::loadTestMesh(test::meshPath(name));
    const ValidatedMesh validated = validate(mesh.view());
    const VoxelizeResult solid = voxelize(mesh.view(), sdfOptions(resolution));
    VoxelizeOptions conservative = sdfOptions(resolution, Mode::Conservative);
    const VoxelizeResult surface = voxelize(mesh.view(), conservative);
    ASSERT_EQ(solid.grid.dims, surface.grid.dims);
    const Oracle oracle(validated, solid.grid);
    const LevelSetVoxels voxels(solid);
    std::uint64_t off_surface[2] = {0, 0}, on_surface[2] = {0, 0}, beyond_band = 0;
    for (int i = 0; i < solid.grid.dims[0]; ++i)
        for (int j = 0; j < solid.grid.dims[1]; ++j)
            for (int k = 0; k < solid.grid.dims[2]; ++k) {
                const LevelSetVoxels::Voxel v = voxels.at(i, j, k);
                EXPECT_EQ(v.inside, v.value < 0 || (v.value == 0 && v.inside)) << i << "," << j << "," << k;
                if (!surface.occupancy.test(i, j, k)) {
                    ASSERT_EQ(v.inside, solid.occupancy.test(i, j, k)) << i << "," << j << "," << k;
                    ++off_surface[v.inside];
                    beyond_band += !v.active && v.inside;
                    continue;
                }
                ASSERT_TRUE(v.active) << i << "," << j << "," << k;
                if (std::fabs(v.value) < 1e-3 * solid.grid.voxel_size) continue;
                const double w = oracle.winding(i, j, k);
                if (std::fabs(w - 0.5) < margin) continue;
                ASSERT_EQ(v.inside, w >= 0.5) << i << "," << j << "," << k << " winding number " << w;
                ++on_surface[v.inside];
            }
    EXPECT_GT(off_surface[0], 100u);
    EXPECT_GT(off_surface[1], 100u);
    EXPECT_GT(on_surface[0], 100u);
    EXPECT_GT(on_surface[1], 100u);
    EXPECT_GT(beyond_band, 0u);  // the inside beyond the band: inactive, -background
    // The sdf's signs come from the inside test in every mode: the surface run's are the same.
    EXPECT_EQ(surface.sdf.values, solid.sdf.values);
    EXPECT_EQ(surface.sdf.leaves.size(), solid.sdf.leaves.size());
}

TEST(SdfSigns, ClosedMeshByRayCrossings) { expectSignsOfTheInsideTest("spot_vcolor.ply", 40, 1e-6); }
TEST(SdfSigns, OpenMeshByWindingNumbers) { expectSignsOfTheInsideTest("elephant_holes.ply", 40, 0.1); }

TEST(SdfGrid, ThinAndTessellationRunsGiveTheSameSdf) {
    // The surface a mode or method draws does not change the sdf: its sign is the inside test
    // on the exact conservative surface.
    const test::TestMesh mesh = test::loadTestMesh(test::meshPath("spot_vcolor.ply"));
    const VoxelizeResult solid = voxelize(mesh.view(), sdfOptions(32));
    const VoxelizeResult thin = voxelize(mesh.view(), sdfOptions(32, Mode::Thin));
    EXPECT_EQ(thin.sdf.values, solid.sdf.values);
    EXPECT_EQ(thin.sdf.inside_runs.size(), solid.sdf.inside_runs.size());
    EXPECT_LT(thin.occupancy.count(), solid.occupancy.count());
}

TEST(SdfGrid, PaddedByTheBand) {
    const test::TestMesh mesh = test::loadTestMesh(test::meshPath("spot_vcolor.ply"));
    VoxelizeOptions plain;
    plain.grid.resolution = 32;
    const VoxelizeResult without = voxelize(mesh.view(), plain);
    for (int band : {1, 5}) {
        const VoxelizeResult with = voxelize(mesh.view(), sdfOptions(32, Mode::Conservative, band));
        for (int a = 0; a < 3; ++a) {
            EXPECT_EQ(with.grid.dims[a], without.grid.dims[a] + 2 * band);
            EXPECT_DOUBLE_EQ(with.grid.origin[a], without.grid.origin[a] - band * with.grid.voxel_size);
        }
        // The same voxels, shifted; the origin's other rounding may move a voxel that only
        // touches the mesh.
        EXPECT_NEAR(double(with.occupancy.count()), double(without.occupancy.count()),
                    0.01 * double(without.occupancy.count()));
    }
}

class CountingInterrupter final : public Interrupter {
public:
    explicit CountingInterrupter(long stop_after) : left_(stop_after) {}
    bool wasInterrupted(int) override { return left_.fetch_sub(1) <= 0; }
    long asked(long started) const { return started - left_.load(); }

private:
    std::atomic<long> left_;
};

TEST(SdfRuns, CancelledAndRefusedOverTheBudget) {
    const test::TestMesh mesh = test::loadTestMesh(test::meshPath("bunny_stanford_69k.ply"));
    // How often a whole run asks, then a stop at every share of that: some of them inside the
    // sdf's own loops; each throws Cancelled, never anything else.
    CountingInterrupter counting(1L << 40);
    const VoxelizeResult whole = voxelize(mesh.view(), sdfOptions(64), &counting);
    const long asks = counting.asked(1L << 40);
    ASSERT_GT(asks, 20);
    for (long stop : {asks / 2, asks * 3 / 4, asks - 3}) {
        CountingInterrupter interrupter(stop);
        EXPECT_THROW(voxelize(mesh.view(), sdfOptions(64), &interrupter), Cancelled) << stop;
    }
    // A budget the surface fits but not the band's leaves.
    VoxelizeOptions tight = sdfOptions(256);
    tight.memory_budget_mib = 24;
    try {
        voxelize(mesh.view(), tight);
        FAIL() << "no ResourceError";
    } catch (const ResourceError& e) {
        EXPECT_NE(std::string(e.what()).find("sdf"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("memory budget"), std::string::npos) << e.what();
    }
    EXPECT_GT(whole.sdf.activeCount(), 0u);
}

// The .vdb's "sdf" read back with OpenVDB.
openvdb::FloatGrid::Ptr writtenLevelSet(const VoxelizeResult& r, const test::TempDir& dir) {
    const std::string path = (dir.path / "sdf.vdb").string();
    writeVdb(r, path);
    openvdb::io::File file(path);
    file.open();
    auto grid = openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGrid("sdf"));
    auto density = file.readGrid("density");
    file.close();
    EXPECT_TRUE(grid && density);
    if (grid && density) {
        EXPECT_EQ(grid->transform(), density->transform());
    }
    return grid;
}

TEST(SdfOpenVdb, LevelSetToolsAcceptItAndMeshItWatertightOnTheSource) {
    vdb::initializeOpenVdb();
    const test::TestMesh mesh = test::loadTestMesh(test::meshPath("spot_vcolor.ply"));
    const ValidatedMesh validated = validate(mesh.view());
    const VoxelizeResult r = voxelize(mesh.view(), sdfOptions(48));
    const test::TempDir dir;
    const auto grid = writtenLevelSet(r, dir);
    ASSERT_TRUE(grid);
    EXPECT_EQ(grid->getGridClass(), openvdb::GRID_LEVEL_SET);
    EXPECT_FLOAT_EQ(grid->background(), float(3 * r.grid.voxel_size));
    EXPECT_EQ(grid->activeVoxelCount(), r.sdf.activeCount());
    // OpenVDB's own checks of a level set: value type, class, uniform voxels, background, no
    // active tiles, finite values, active values within the band, inactive values ±background.
    EXPECT_EQ(openvdb::tools::checkLevelSet(*grid, 8), "");
    // Its ninth, |∇d| within [0.5, 1.5] by central differences, fails on the medial axis of
    // thin parts (Spot's ears and horns: a voxel between two close surfaces), as for any
    // exact distance: a few voxels only.
    openvdb::tools::Diagnose<openvdb::FloatGrid> diagnose(*grid);
    openvdb::tools::CheckNormGrad<openvdb::FloatGrid> norm_grad(*grid, 0.5, 1.5);
    diagnose.check(norm_grad, false, true, false, false);
    EXPECT_LT(double(diagnose.failureCount()), 1e-3 * double(r.sdf.activeCount()));
    // volumeToMesh: a closed surface (every edge used by exactly two faces) on the source.
    std::vector<openvdb::Vec3s> points;
    std::vector<openvdb::Vec3I> triangles;
    std::vector<openvdb::Vec4I> quads;
    openvdb::tools::volumeToMesh(*grid, points, triangles, quads, 0.0, 0.0);
    ASSERT_GT(quads.size() + triangles.size(), 1000u);
    std::map<std::pair<unsigned, unsigned>, int> edges;
    auto addEdge = [&](unsigned a, unsigned b) { ++edges[{std::min(a, b), std::max(a, b)}]; };
    for (const auto& q : quads)
        for (int c = 0; c < 4; ++c) addEdge(q[c], q[(c + 1) % 4]);
    for (const auto& t : triangles)
        for (int c = 0; c < 3; ++c) addEdge(t[c], t[(c + 1) % 3]);
    std::size_t open_edges = 0;
    for (const auto& [edge, uses] : edges) open_edges += uses != 2;
    EXPECT_EQ(open_edges, 0u);
    const Oracle oracle(validated, r.grid);
    std::vector<double> off;
    for (std::size_t n = 0; n < points.size(); n += 7)  // volumeToMesh's points are world positions
        off.push_back(oracle.distanceFrom(r.grid.toVoxel(Vec3{points[n][0], points[n][1], points[n][2]}), 10.0));
    std::sort(off.begin(), off.end());
    EXPECT_LT(off[off.size() / 2], 0.05);  // voxels
    EXPECT_LT(off.back(), 0.5);
}

TEST(SdfOpenVdb, OpenMeshSignSurvivesWhereTheFloodFillLeaks) {
    // OpenVDB's meshToLevelSet on the same transform and band: its sign comes from a flood fill
    // from outside, which leaks through the elephant's holes. Where the two signs differ on
    // voxels both hold in the band, the exact winding number decides: hyvox right everywhere
    // it is clear (|w - 0.5| >= 0.1), OpenVDB wrong on a counted share.
    vdb::initializeOpenVdb();
    const test::TestMesh mesh = test::loadTestMesh(test::meshPath("elephant_holes.ply"));
    const ValidatedMesh validated = validate(mesh.view());
    const VoxelizeResult r = voxelize(mesh.view(), sdfOptions(64));
    const auto transform = vdb::makeTransform(r.grid);
    std::vector<openvdb::Vec3s> points(mesh.positions.size() / 3);
    for (std::size_t v = 0; v < points.size(); ++v)
        points[v] = openvdb::Vec3s(transform->worldToIndex(
            openvdb::Vec3d(mesh.positions[3 * v], mesh.positions[3 * v + 1], mesh.positions[3 * v + 2])));
    std::vector<openvdb::Vec3I> triangles(mesh.triangles.size() / 3);
    for (std::size_t t = 0; t < triangles.size(); ++t)
        triangles[t] = openvdb::Vec3I(mesh.triangles[3 * t], mesh.triangles[3 * t + 1], mesh.triangles[3 * t + 2]);
    openvdb::tools::QuadAndTriangleDataAdapter<openvdb::Vec3s, openvdb::Vec3I> adapter(points, triangles);
    const auto theirs = openvdb::tools::meshToVolume<openvdb::FloatGrid>(adapter, *transform, 3.0f, 3.0f);
    const Oracle oracle(validated, r.grid);
    const LevelSetVoxels voxels(r);
    auto accessor = theirs->getConstAccessor();
    std::uint64_t differ = 0, hyvox_right = 0, openvdb_right = 0, unclear = 0;
    for (auto it = theirs->cbeginValueOn(); it; ++it) {
        const openvdb::Coord c = it.getCoord();
        if (!r.occupancy.inside(c.x(), c.y(), c.z())) continue;
        const LevelSetVoxels::Voxel ours = voxels.at(c.x(), c.y(), c.z());
        if (!ours.active || std::fabs(ours.value) < 0.05 * r.grid.voxel_size) continue;
        if ((ours.value < 0) == (*it < 0)) continue;
        ++differ;
        if (differ % 4) continue;  // a sample of them for the exact winding number
        const double w = oracle.winding(c.x(), c.y(), c.z());
        if (std::fabs(w - 0.5) < 0.1) {
            ++unclear;
            continue;
        }
        ++(((ours.value < 0) == (w >= 0.5)) ? hyvox_right : openvdb_right);
    }
    RecordProperty("differing_voxels", std::to_string(differ));
    EXPECT_GT(differ, 500u);
    EXPECT_EQ(openvdb_right, 0u);
    EXPECT_GT(hyvox_right, 100u);
    EXPECT_LT(unclear, hyvox_right / 4);
}

}  // namespace
}  // namespace hyvox
