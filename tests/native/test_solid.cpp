// SPDX-License-Identifier: GPL-3.0-or-later
// Solid mode's pieces against oracles of their own: the sparse grid's tiles against a dense
// bit grid, the ray crossings on rays that pass exactly through shared edges and vertices
// against an octahedron's inequality, the solid angles against the octahedron's inside, fast
// winding numbers (one point at a time, and a box of points at once with a local expansion)
// against the exact sum of solid angles.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "hyvox/errors.h"
#include "hyvox/sparse_grid.h"
#include "hyvox/voxelize.h"
#include "solid/brick_samples.h"
#include "solid/edge_closure.h"
#include "solid/fast_winding.h"
#include "solid/fill_inside.h"
#include "solid/local_expansion.h"
#include "solid/ray_crossings.h"
#include "solid/sheet_sum.h"
#include "solid/sheet_winding.h"
#include "support/mesh_arrays.h"
#include "support/test_mesh_loader.h"

namespace hyvox {
namespace {

// A dense grid with whole bricks set (some cut by the grid's edge) and scattered voxels.
BitGrid patchwork(std::array<std::int32_t, 3> dims, unsigned seed) {
    BitGrid dense(dims);
    std::mt19937 rng(seed);
    const BrickLayout& b = dense.bricks();
    for (int bx = 0; bx < b.counts[0]; ++bx)
        for (int by = 0; by < b.counts[1]; ++by)
            for (int bz = 0; bz < b.counts[2]; ++bz) {
                const unsigned kind = rng() % 3;  // empty, whole, scattered
                for (int i = 8 * bx; i < std::min(8 * bx + 8, dims[0]); ++i)
                    for (int j = 8 * by; j < std::min(8 * by + 8, dims[1]); ++j)
                        for (int k = 8 * bz; k < std::min(8 * bz + 8, dims[2]); ++k)
                            if (kind == 1 || (kind == 2 && rng() % 5 == 0)) dense.set(i, j, k);
            }
    return dense;
}

std::uint64_t wholeSetBricks(const BitGrid& dense) {
    std::uint64_t whole = 0;
    const BrickLayout& b = dense.bricks();
    for (std::size_t n = 0; n < b.total(); ++n) {
        const auto at = b.at(n);
        bool inside = true, all = true;
        for (int a = 0; a < 3; ++a) inside = inside && 8 * at[a] + 8 <= dense.dims()[a];
        for (int w = 0; w < 8; ++w) all = all && dense.data()[n * 8 + std::size_t(w)] == ~0ull;
        whole += inside && all;
    }
    return whole;
}

TEST(SolidSparseGrid, WholeBricksBecomeTilesAndEverythingElseSeesTheirVoxels) {
    const BitGrid dense = patchwork({37, 24, 19}, 7);
    const SparseGrid sparse = SparseGrid::fromBitGrid(dense);
    EXPECT_GT(sparse.tileCount(), 0u);
    EXPECT_EQ(sparse.tileCount(), wholeSetBricks(dense));
    EXPECT_EQ(sparse.leafCount() + sparse.tileCount(), [&] {
        std::size_t bricks = 0;
        for (std::size_t n = 0; n < dense.brickCount(); ++n)
            bricks +=
                std::any_of(dense.data() + n * 8, dense.data() + n * 8 + 8, [](std::uint64_t w) { return w != 0; });
        return bricks;
    }());
    EXPECT_EQ(sparse.count(), dense.count());
    EXPECT_TRUE(sparse.toBitGrid() == dense);
    auto listed = sparse.coords(), expected = dense.coords();
    std::sort(listed.begin(), listed.end());
    std::sort(expected.begin(), expected.end());
    EXPECT_EQ(listed, expected);
    for (int i = 0; i < 37; ++i)
        for (int j = 0; j < 24; ++j)
            for (int k = 0; k < 19; ++k)
                ASSERT_EQ(sparse.test(i, j, k), dense.test(i, j, k)) << i << "," << j << "," << k;
}

TEST(SolidSparseGrid, MergeIsTheUnionWhateverTheVoxelsCameAs) {
    const BitGrid a = patchwork({40, 17, 33}, 1), b = patchwork({40, 17, 33}, 2);
    BitGrid both(a.dims());
    for (std::size_t w = 0; w < both.wordCount(); ++w) both.data()[w] = a.data()[w] | b.data()[w];
    SparseGrid merged = SparseGrid::fromBitGrid(a);
    merged.merge(SparseGrid::fromBitGrid(b));
    merged.finish();
    EXPECT_TRUE(merged == SparseGrid::fromBitGrid(both));
    EXPECT_EQ(merged.count(), both.count());
    // A run of tiles equals the same bricks set voxel by voxel: bricks 1 and 2 of a 2x2x2
    // layout are (0,0,1) and (0,1,0).
    SparseGrid run({16, 16, 16}), voxels({16, 16, 16});
    run.addTileRun(1, 3);
    run.finish();
    for (int i = 0; i < 8; ++i)
        for (int j = 0; j < 8; ++j)
            for (int k = 0; k < 8; ++k) {
                voxels.set(i, j, k + 8);
                voxels.set(i, j + 8, k);
            }
    voxels.finish();
    EXPECT_TRUE(run == voxels);
    EXPECT_EQ(voxels.tileCount(), 2u);
    EXPECT_EQ(run.count(), 1024u);
    EXPECT_TRUE(run.test(0, 8, 0) && run.test(7, 7, 15) && !run.test(0, 0, 0) && !run.test(7, 15, 15));
    EXPECT_THROW(SparseGrid({12, 16, 16}).addTileRun(4, 5), std::invalid_argument);  // cut by the edge
}

// An octahedron |x-c| + |y-c| + |z-c| <= r whose six corners sit on voxel centres: the rays
// through the centre column hit its top and bottom corners, and those through x = c or y = c
// run along its edges, exactly.
struct Octahedron {
    double c = 8.5, r = 6.0;
    std::vector<float> positions;
    std::vector<std::uint32_t> triangles;
    Octahedron() {
        const double p[6][3] = {{c + r, c, c}, {c - r, c, c}, {c, c + r, c},
                                {c, c - r, c}, {c, c, c + r}, {c, c, c - r}};
        for (const auto& v : p)
            for (double x : v) positions.push_back(float(x));
        // Outward: for each octant (sx, sy, sz) the face (x, y, z corners) ordered counter-clockwise.
        for (int sx = 0; sx < 2; ++sx)
            for (int sy = 0; sy < 2; ++sy)
                for (int sz = 0; sz < 2; ++sz) {
                    std::uint32_t a = std::uint32_t(sx), b = std::uint32_t(2 + sy), d = std::uint32_t(4 + sz);
                    const bool flip = (sx + sy + sz) % 2 == 1;
                    triangles.insert(triangles.end(), {a, flip ? d : b, flip ? b : d});
                }
    }
    bool inside(int i, int j, int k) const {
        return std::fabs(i + 0.5 - c) + std::fabs(j + 0.5 - c) + std::fabs(k + 0.5 - c) < r;
    }
};

TEST(SolidRays, SharedEdgesAndVerticesOnRaysCountOnce) {
    const Octahedron oct;
    for (const InsideRule rule : {InsideRule::Parity, InsideRule::Auto, InsideRule::Winding}) {
        SCOPED_TRACE(toString(rule));
        VoxelizeOptions solid;
        solid.mode = Mode::Solid;
        solid.solid.inside = rule;
        solid.grid.voxel_size = 1.0;
        solid.grid.origin = std::array<double, 3>{0, 0, 0};
        solid.grid.bounds = Bounds{{0, 0, 0}, {17, 17, 17}};
        VoxelizeOptions surface = solid;
        surface.mode = Mode::Conservative;
        const auto view = test::viewOf(oct.positions, oct.triangles);
        const VoxelizeResult filled = voxelize(view, solid);
        const VoxelizeResult shell = voxelize(view, surface);
        ASSERT_EQ(filled.stats.solid->boundary_edges + filled.stats.solid->misoriented_edges, 0u);
        int checked_on_corner_rays = 0;
        for (int i = 0; i < 17; ++i)
            for (int j = 0; j < 17; ++j)
                for (int k = 0; k < 17; ++k) {
                    if (shell.occupancy.test(i, j, k)) {
                        ASSERT_TRUE(filled.occupancy.test(i, j, k));
                        continue;
                    }
                    ASSERT_EQ(filled.occupancy.test(i, j, k), oct.inside(i, j, k)) << i << "," << j << "," << k;
                    checked_on_corner_rays += (i == 8 || j == 8);
                }
        EXPECT_GT(checked_on_corner_rays, 50);  // voxels whose ray runs through an edge or corner
    }
}

// A usable triangle with a vertex past the rays' fixed-point range (2^40 voxels: bounds far
// smaller than the mesh) is refused with the reason, whichever thread's chunk meets it.
TEST(SolidRays, UsableVertexPastTheFixedPointRangeIsRefused) {
    Octahedron oct;
    const auto far = std::uint32_t(oct.positions.size() / 3);
    oct.positions.insert(oct.positions.end(), {1e30f, 0, 0, 1e30f, 1, 0, 1e30f, 0, 1});
    // Many triangles before it, so that it lies in a later chunk than the first.
    for (int n = 0; n < 40000; ++n) oct.triangles.insert(oct.triangles.end(), {0, 1, 2});
    oct.triangles.insert(oct.triangles.end(), {far, far + 1, far + 2});
    VoxelizeOptions solid;
    solid.mode = Mode::Solid;
    solid.solid.inside = InsideRule::Parity;
    solid.grid.bounds =
        Bounds{{oct.c - oct.r, oct.c - oct.r, oct.c - oct.r}, {oct.c + oct.r, oct.c + oct.r, oct.c + oct.r}};
    solid.grid.resolution = 12;
    try {
        voxelize(test::viewOf(oct.positions, oct.triangles), solid);
        FAIL() << "the far vertex was taken";
    } catch (const InvalidInput& e) {
        EXPECT_NE(std::string(e.what()).find("more than 2^40 voxels from the grid"), std::string::npos) << e.what();
    }
}

// fuzz_solid's first finding (tests/fuzz/seeds/solid/degenerate_needle_past_the_rays.bin): a
// degenerate triangle (no area: validate() skips it) may reach far past the grid, which only
// the usable triangles bound. The rays refused the whole mesh for its far vertex ("more than
// 2^40 voxels from the grid") under parity and auto, while winding took it. Every rule now
// fills the octahedron as without the needle, whether the needle is open (three boundary
// edges) or doubled back on itself (every edge used once each way: auto counts crossings).
TEST(SolidRays, DegenerateNeedleFarPastTheGridIsNoReasonToRefuse) {
    for (const bool doubled : {false, true}) {
        Octahedron oct;
        const std::uint32_t near = std::uint32_t(oct.positions.size() / 3);
        const float y = float(oct.c), z = float(oct.c);
        oct.positions.insert(oct.positions.end(), {float(oct.c + oct.r + 1), y, z, 1e30f, y, z});
        oct.triangles.insert(oct.triangles.end(), {0, near, near + 1});  // collinear along x
        if (doubled) oct.triangles.insert(oct.triangles.end(), {0, near + 1, near});
        for (const InsideRule rule : {InsideRule::Parity, InsideRule::Auto, InsideRule::Winding}) {
            SCOPED_TRACE(std::string(toString(rule)) + (doubled ? ", doubled needle" : ", open needle"));
            VoxelizeOptions solid;
            solid.mode = Mode::Solid;
            solid.solid.inside = rule;
            solid.grid.resolution = 12;
            solid.grid.padding = 1;
            VoxelizeOptions surface = solid;
            surface.mode = Mode::Conservative;
            const auto view = test::viewOf(oct.positions, oct.triangles);
            const VoxelizeResult filled = voxelize(view, solid);
            const VoxelizeResult shell = voxelize(view, surface);
            ASSERT_EQ(filled.stats.triangles_degenerate, doubled ? 2u : 1u);
            ASSERT_EQ(filled.stats.solid->boundary_edges, doubled ? 0u : 3u);
            const GridSpec& grid = filled.grid;
            int inside = 0;
            for (int i = 0; i < grid.dims[0]; ++i)
                for (int j = 0; j < grid.dims[1]; ++j)
                    for (int k = 0; k < grid.dims[2]; ++k) {
                        if (shell.occupancy.test(i, j, k)) {
                            ASSERT_TRUE(filled.occupancy.test(i, j, k));
                            continue;
                        }
                        const auto p = grid.voxelCentre(i, j, k);
                        const bool expected =
                            std::fabs(p[0] - oct.c) + std::fabs(p[1] - oct.c) + std::fabs(p[2] - oct.c) < oct.r;
                        ASSERT_EQ(filled.occupancy.test(i, j, k), expected) << i << "," << j << "," << k;
                        inside += expected;
                    }
            EXPECT_GT(inside, 50);
        }
    }
}

// The exact sum that FastWindingNumbersMatchTheExactSum takes as its oracle, against the
// winding number of a closed, outward-wound mesh: 1 at every point inside, 0 outside.
TEST(SolidWinding, TriangleSolidAnglesSumToTheOctahedronsInside) {
    const Octahedron oct;
    auto corner = [&](std::uint32_t v) {
        return solid::Vec3{oct.positions[3 * v], oct.positions[3 * v + 1], oct.positions[3 * v + 2]};
    };
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(oct.c - oct.r - 1, oct.c + oct.r + 1);  // about 1 in 8 inside
    int inside = 0, outside = 0;
    for (int n = 0; n < 200; ++n) {
        const solid::Vec3 q{u(rng), u(rng), u(rng)};
        const double l1 = std::fabs(q[0] - oct.c) + std::fabs(q[1] - oct.c) + std::fabs(q[2] - oct.c);
        if (std::fabs(l1 - oct.r) < 1e-3) continue;  // on the surface: undefined
        double sum = 0;
        for (std::size_t t = 0; t < oct.triangles.size(); t += 3)
            sum += solid::triangleWinding(corner(oct.triangles[t]), corner(oct.triangles[t + 1]),
                                          corner(oct.triangles[t + 2]), q);
        EXPECT_NEAR(sum, l1 < oct.r ? 1.0 : 0.0, 1e-9) << q[0] << "," << q[1] << "," << q[2];
        ++(l1 < oct.r ? inside : outside);
    }
    EXPECT_GT(inside, 10);
    EXPECT_GT(outside, 10);
}

// A mesh's triangles in a grid's voxel space, and the exact double-precision winding number
// at a point there (every triangle's solid angle summed: the oracle of the tests below).
struct VoxelTriangles {
    VoxelTriangles(const std::vector<float>& positions, const std::vector<std::uint32_t>& triangles,
                   const GridSpec& grid) {
        for (std::size_t t = 0; t < triangles.size(); t += 3) {
            std::array<solid::Vec3, 3> c;
            for (std::size_t k = 0; k < 3; ++k) {
                const float* p = &positions[3 * std::size_t(triangles[t + k])];
                c[k] = grid.toVoxel(std::array<double, 3>{p[0], p[1], p[2]});
            }
            corners.push_back(c);
        }
    }
    // The usable triangles of a validated mesh.
    VoxelTriangles(const ValidatedMesh& mesh, const GridSpec& grid) {
        for (const std::uint32_t t : mesh.usable)
            corners.push_back(
                {grid.toVoxel(mesh.vertex(t, 0)), grid.toVoxel(mesh.vertex(t, 1)), grid.toVoxel(mesh.vertex(t, 2))});
    }
    double winding(const solid::Vec3& q) const {
        double sum = 0;
        for (const auto& c : corners) sum += solid::triangleWinding(c[0], c[1], c[2], q);
        return sum;
    }
    std::vector<std::array<solid::Vec3, 3>> corners;
};

TEST(SolidWinding, FastWindingNumbersMatchTheExactSum) {
    const test::TestMesh mesh = test::loadTestMesh(test::meshPath("bunny_stanford_69k.ply"));
    const ValidatedMesh validated = validate(test::viewOf(mesh.positions, mesh.triangles));
    GridOptions options;
    options.resolution = 32;
    const GridSpec grid = makeGrid(validated.bounds, options);
    // beta = 1e9 opens every cluster: the exact sum. Finite beta: an error within the margin
    // the decisions are tested with (|w - 0.5| >= 0.05), falling as beta grows (second order:
    // about beta^-2).
    const solid::FastWinding sharp(validated, grid, 1e9);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-4.0, 36.0);
    std::vector<solid::Vec3> points;
    const VoxelTriangles triangles(validated, grid);
    std::vector<double> exact;
    for (int n = 0; n < 40; ++n) {
        points.push_back({u(rng), u(rng), u(rng)});
        const double sum = triangles.winding(points.back());
        exact.push_back(sum);
        EXPECT_NEAR(sharp.at(points.back()), sum, 1e-9);
    }
    auto worstError = [&](double beta) {
        const solid::FastWinding fast(validated, grid, beta);
        double worst = 0;
        for (std::size_t n = 0; n < points.size(); ++n)
            worst = std::max(worst, std::fabs(fast.at(points[n]) - exact[n]));
        return worst;
    };
    const double at2 = worstError(2.0), at8 = worstError(8.0);
    EXPECT_LT(at2, 0.05);
    EXPECT_LT(at8, at2 / 10);
}

// The float, vectorised sum of the open edges' sheets (solid/sheet_sum.h) against each sheet
// as two tall triangles (1e9 voxels: the missing top adds under 1e-8), summed in double with
// triangleWinding, at grid-sized coordinates (near 1000), with edges up to 600 voxels long and
// sheets standing 500 voxels below the points (float cancellation would show there).
TEST(SolidWinding, FloatSheetSumMatchesTallTriangles) {
    std::mt19937 rng(11);
    const solid::Vec3 origin{1000, 700, 900};
    std::uniform_real_distribution<double> near(-20.0, 28.0), span(-300.0, 300.0), inside(0.0, 9.0);
    double worst = 0;
    int tested = 0, poisoned = 0;
    for (const bool upward : {false, true}) {
        std::vector<solid::GradientBound::Sheet> sheets;
        for (int n = 0; n < 1000; ++n) {
            solid::GradientBound::Sheet s;
            const bool longer = n % 4 == 0;
            for (int k = 0; k < 3; ++k) {
                s.a[k] = origin[k] + near(rng);
                s.b[k] = s.a[k] + (longer ? span(rng) : near(rng) / 4);
            }
            if (n % 50 == 0) s.b[0] = s.a[0], s.b[1] = s.a[1];  // vertical edges too
            if (n % 5 == 1) {                                   // far below the box (above it for rays up): tall sheets
                const double drop = upward ? 500.0 : -500.0;
                s.a[2] += drop, s.b[2] += drop;
            }
            s.excess = 1 + n % 3;
            sheets.push_back(s);
        }
        solid::SheetSum sum;
        sum.assign(sheets, upward, origin);
        const double height = upward ? -1e9 : 1e9;
        for (int n = 0; n < 200; ++n) {
            const solid::Vec3 q{origin[0] + inside(rng), origin[1] + inside(rng), origin[2] + inside(rng)};
            double exact = 0, closest = HUGE_VAL;
            for (const auto& s : sheets) {
                const solid::Vec3 a_top{s.a[0], s.a[1], s.a[2] + height}, b_top{s.b[0], s.b[1], s.b[2] + height};
                exact += s.excess *
                    (solid::triangleWinding(s.b, s.a, a_top, q) + solid::triangleWinding(s.b, a_top, b_top, q));
                // The distance in xy from q's column to the edge.
                const double dx = s.b[0] - s.a[0], dy = s.b[1] - s.a[1], length2 = dx * dx + dy * dy;
                const double px = q[0] - s.a[0], py = q[1] - s.a[1];
                const double t = length2 > 0 ? std::clamp((px * dx + py * dy) / length2, 0.0, 1.0) : 0.0;
                closest = std::min(closest, std::hypot(px - t * dx, py - t * dy));
            }
            const double value = sum.at(q);
            if (closest < 0.9e-3) {  // the column meets an edge: no value
                EXPECT_TRUE(std::isnan(value));
                ++poisoned;
            } else if (closest > 1.1e-3) {
                ASSERT_FALSE(std::isnan(value));
                worst = std::max(worst, std::fabs(value - exact));
                ++tested;
            }
        }
        // Columns through an edge, 1e-4 voxel beside it: no value.
        for (std::size_t n = 2; n < sheets.size(); n += 25) {
            const auto& s = sheets[n];
            const solid::Vec3 q{0.5 * (s.a[0] + s.b[0]) + 1e-4, 0.5 * (s.a[1] + s.b[1]), origin[2] + 4.5};
            EXPECT_TRUE(std::isnan(sum.at(q))) << n;
            ++poisoned;
        }
    }
    EXPECT_GT(tested, 300);
    EXPECT_LT(worst, 5e-5);
    std::printf("float sheet sums: %d points, worst error %.3g, %d columns on an edge\n", tested, worst, poisoned);
}

// A column's sheet sums together (SheetSum::atColumn) against at() point by point: the same
// bits, rays down and up, with a column that passes an edge (NaN both ways) and one point.
TEST(SolidWinding, ColumnOfSheetSumsEqualsPointByPoint) {
    std::mt19937 rng(13);
    const solid::Vec3 origin{200, 300, 400};
    std::uniform_real_distribution<double> near(-10.0, 18.0), inside(0.0, 9.0);
    for (const bool upward : {false, true}) {
        std::vector<solid::GradientBound::Sheet> sheets;
        for (int n = 0; n < 37; ++n) {  // not a multiple of the lanes
            solid::GradientBound::Sheet s;
            for (int k = 0; k < 3; ++k) {
                s.a[k] = origin[k] + near(rng);
                s.b[k] = s.a[k] + near(rng) / 3;
            }
            s.excess = 1 + n % 2;
            sheets.push_back(s);
        }
        // An edge through the column (x, y) = origin + (4.5, 4.5): that column has no value.
        sheets[5].a = {origin[0] + 3.5, origin[1] + 3.5, origin[2] + 1.0};
        sheets[5].b = {origin[0] + 5.5, origin[1] + 5.5, origin[2] + 2.0};
        solid::SheetSum sum;
        sum.assign(sheets, upward, origin);
        int columns = 0, poisoned = 0;
        for (int n = 0; n < 40; ++n) {
            const double x = origin[0] + (n == 0 ? 4.5 : inside(rng)), y = origin[1] + (n == 0 ? 4.5 : inside(rng));
            const int count = n % 9 + 1;
            double heights[9], values[9];
            for (int k = 0; k < count; ++k) heights[k] = origin[2] + inside(rng);
            sum.atColumn(x, y, heights, count, values);
            for (int k = 0; k < count; ++k) {
                const double one = sum.at({x, y, heights[k]});
                if (std::isnan(one)) {
                    EXPECT_TRUE(std::isnan(values[k]));
                    ++poisoned;
                } else {
                    EXPECT_EQ(values[k], one) << n << " " << k;
                }
            }
            ++columns;
        }
        EXPECT_GT(poisoned, 0);
        EXPECT_EQ(columns, 40);
    }
}

// A brick's columns found together (RayCrossings::columns) against one column at a time.
TEST(SolidRays, BlockOfColumnsEqualsColumnByColumn) {
    const test::TestMesh mesh = test::loadTestMesh(test::meshPath("bunny_stanford_69k.ply"));
    const ValidatedMesh validated = validate(test::viewOf(mesh.positions, mesh.triangles));
    GridOptions options;
    options.resolution = 44;
    const GridSpec grid = makeGrid(validated.bounds, options);
    const solid::RayCrossings rays(validated, grid);
    auto sorted = [](std::vector<solid::RayCrossings::Crossing> list) {
        std::sort(list.begin(), list.end(),
                  [](const auto& a, const auto& b) { return a.z < b.z || (a.z == b.z && a.sign < b.sign); });
        return list;
    };
    std::size_t crossings = 0;
    for (int i0 = 0; i0 < grid.dims[0]; i0 += 8)
        for (int j0 = 0; j0 < grid.dims[1]; j0 += 8) {
            const int ni = std::min(9, grid.dims[0] - i0), nj = std::min(9, grid.dims[1] - j0);
            std::vector<std::vector<solid::RayCrossings::Crossing>> block(std::size_t(ni * nj));
            rays.columns(i0, j0, ni, nj, block.data());
            for (int i = i0; i < i0 + ni; ++i)
                for (int j = j0; j < j0 + nj; ++j) {
                    std::vector<solid::RayCrossings::Crossing> one;
                    rays.column(i, j, one);
                    const auto a = sorted(block[std::size_t((i - i0) * nj + (j - j0))]), b = sorted(one);
                    ASSERT_EQ(a.size(), b.size()) << i << "," << j;
                    for (std::size_t n = 0; n < a.size(); ++n) {
                        EXPECT_EQ(a[n].z, b[n].z);
                        EXPECT_EQ(a[n].sign, b[n].sign);
                    }
                    crossings += a.size();
                }
        }
    EXPECT_GT(crossings, 1000u);
}

// The points of a brick evaluated in one walk of the tree (FastWinding::atMany) against one
// at a time: the same values to the bit.
TEST(SolidWinding, ManyPointsAtOnceEqualOneAtATime) {
    const test::TestMesh mesh = test::loadTestMesh(test::meshPath("bunny_stanford_69k.ply"));
    const ValidatedMesh validated = validate(test::viewOf(mesh.positions, mesh.triangles));
    GridOptions options;
    options.resolution = 64;
    const GridSpec grid = makeGrid(validated.bounds, options);
    const solid::FastWinding winding(validated, grid, 2.0);
    std::mt19937 rng(8);
    std::uniform_real_distribution<double> u(-4.0, 68.0), brick(0.0, 9.0);
    for (int batch = 0; batch < 20; ++batch) {
        // Clustered like a brick's voxels, or spread over the grid.
        const solid::Vec3 corner{u(rng), u(rng), u(rng)};
        std::vector<solid::Vec3> points;
        for (int n = 0; n < 1 + batch * 7; ++n)
            points.push_back(batch % 2
                                 ? solid::Vec3{corner[0] + brick(rng), corner[1] + brick(rng), corner[2] + brick(rng)}
                                 : solid::Vec3{u(rng), u(rng), u(rng)});
        std::vector<double> many(points.size());
        winding.atMany(points.data(), points.size(), many.data());
        for (std::size_t n = 0; n < points.size(); ++n) EXPECT_EQ(many[n], winding.at(points[n])) << batch << " " << n;
    }
}

// The far field of clusters as one polynomial about a box's centre (solid/local_expansion.h)
// against the clusters' second-order fields (FastWinding's formula) summed point by point:
// the part the cut after order 3 leaves out is about (box radius / distance)^4 of the field.
TEST(SolidWinding, LocalExpansionMatchesTheClustersFieldsPointByPoint) {
    std::mt19937 rng(12);
    std::uniform_real_distribution<double> unit(-1.0, 1.0), spread(0.0, 1.0);
    const solid::Vec3 centre{40.0, -7.0, 13.0};
    const double rho = 7.0;
    // The fast winding numbers' far field of a cluster at q, times 4π (solid/fast_winding.cpp).
    struct Cluster {
        solid::Vec3 c, area;
        std::array<double, 9> moment;
    };
    auto field = [](const Cluster& k, const solid::Vec3& q) {
        const solid::Vec3 r{k.c[0] - q[0], k.c[1] - q[1], k.c[2] - q[2]};
        const double r2 = r[0] * r[0] + r[1] * r[1] + r[2] * r[2], r1 = std::sqrt(r2), r3 = r2 * r1;
        double rmr = 0;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) rmr += r[i] * k.moment[3 * i + j] * r[j];
        const double trace = k.moment[0] + k.moment[4] + k.moment[8];
        return (k.area[0] * r[0] + k.area[1] * r[1] + k.area[2] * r[2]) / r3 + trace / r3 - 3.0 * rmr / (r3 * r2);
    };
    for (const double kappa : {3.0, 10.0}) {
        // 100 clusters (more than three batches), each between kappa rho and 4 kappa rho away,
        // of area vectors and moments of a cluster of radius up to the distance / 2.
        std::vector<Cluster> clusters;
        solid::LocalExpansion expansion;
        expansion.reset(centre);
        for (int n = 0; n < 100; ++n) {
            solid::Vec3 direction{unit(rng), unit(rng), unit(rng)};
            const double length =
                std::sqrt(direction[0] * direction[0] + direction[1] * direction[1] + direction[2] * direction[2]);
            const double d = kappa * rho * (1.0 + 3.0 * spread(rng));
            Cluster k;
            for (int i = 0; i < 3; ++i) k.c[i] = centre[i] + d * direction[i] / length, k.area[i] = 50.0 * unit(rng);
            for (double& m : k.moment) m = 50.0 * 0.5 * d * unit(rng);
            expansion.add(k.c, k.area, n % 3 ? &k.moment : nullptr);
            if (n % 3 == 0) k.moment.fill(0.0);
            clusters.push_back(k);
        }
        double worst = 0;
        for (int n = 0; n < 200; ++n) {
            solid::Vec3 q;
            do q = {unit(rng), unit(rng), unit(rng)};
            while (q[0] * q[0] + q[1] * q[1] + q[2] * q[2] > 1.0);
            for (int i = 0; i < 3; ++i) q[i] = centre[i] + rho * q[i];
            double direct = 0, size = 0;
            for (const Cluster& k : clusters) {
                direct += field(k, q);
                size += std::fabs(field(k, q));
            }
            worst = std::max(worst, std::fabs(expansion.at(q) - direct) / size);
        }
        // About (1/kappa)^4 (1.2e-2 and 1e-4; measured 1.0e-2 and 6.4e-5), with room.
        EXPECT_LT(worst, 1.6 / std::pow(kappa, 4)) << kappa;
    }
}

// Sponza (open, large triangles cut into pieces) validated on a grid of `resolution`, with
// its triangles in voxel space for the exact winding number.
struct SponzaOnGrid {
    explicit SponzaOnGrid(int resolution)
        : mesh(test::loadTestMesh(test::meshPath("sponza_crytek_262k_vcolor.ply.gz"))),
          validated(validate(mesh.view())),
          grid(makeGrid(validated.bounds,
                        [&] {
                            GridOptions options;
                            options.resolution = resolution;
                            return options;
                        }())),
          triangles(validated, grid) {}
    double exactWinding(const solid::Vec3& q) const { return triangles.winding(q); }
    test::TestMesh mesh;
    ValidatedMesh validated;  // views mesh's arrays
    GridSpec grid;
    VoxelTriangles triangles;
};

// FastWinding::atBox, a box of points at once (solid/box_winding.cpp), on Sponza (open, large
// triangles cut into pieces) at 128: against at() point by point and against the exact sum of
// the triangles' solid angles, in boxes the size of a brick all over the grid. With every
// cluster opened (beta 1e9) it is the exact sum (summed in float); at beta 2 its error is that of the fast
// winding numbers themselves (within the margin the decisions are tested with) and no larger
// than at()'s on average.
TEST(SolidWinding, BoxOfPointsMatchesOneAtATimeAndTheExactSum) {
    const SponzaOnGrid sponza(128);
    const ValidatedMesh& validated = sponza.validated;
    const GridSpec& grid = sponza.grid;
    auto exact = [&](const solid::Vec3& q) { return sponza.exactWinding(q); };
    std::mt19937 rng(5);
    auto boxOfPoints = [&](int count) {
        std::array<int, 3> brick;
        for (int d = 0; d < 3; ++d) brick[d] = 8 * int(rng() % std::uint32_t((grid.dims[d] + 7) / 8));
        std::vector<solid::Vec3> points;
        for (int n = 0; n < count; ++n)
            points.push_back(
                {brick[0] + int(rng() % 8) + 0.5, brick[1] + int(rng() % 8) + 0.5, brick[2] + int(rng() % 8) + 0.5});
        return points;
    };
    {
        const solid::FastWinding sharp(validated, grid, 1e9);
        for (int box = 0; box < 2; ++box) {
            const std::vector<solid::Vec3> points = boxOfPoints(12);
            std::vector<double> values(points.size());
            sharp.atBox(points.data(), points.size(), values.data());
            // Every triangle near: the float sum of 378k pieces (measured within 5e-8).
            for (std::size_t n = 0; n < points.size(); ++n) EXPECT_NEAR(values[n], exact(points[n]), 1e-6);
        }
    }
    const solid::FastWinding fast(validated, grid, 2.0);
    double worst_vs_at = 0, worst_box = 0, worst_at = 0, sum_box = 0, sum_at = 0;
    int checked = 0;
    for (int box = 0; box < 40; ++box) {
        const std::vector<solid::Vec3> points = boxOfPoints(64);
        std::vector<double> values(points.size());
        fast.atBox(points.data(), points.size(), values.data());
        for (std::size_t n = 0; n < points.size(); ++n) {
            const double one = fast.at(points[n]);
            worst_vs_at = std::max(worst_vs_at, std::fabs(values[n] - one));
            if (n % 16) continue;
            const double w = exact(points[n]);
            worst_box = std::max(worst_box, std::fabs(values[n] - w));
            worst_at = std::max(worst_at, std::fabs(one - w));
            sum_box += std::fabs(values[n] - w);
            sum_at += std::fabs(one - w);
            ++checked;
        }
    }
    std::printf(
        "atBox - at(): max %.3g; vs the exact sum over %d points: atBox max %.3g mean %.3g, at() max %.3g mean %.3g\n",
        worst_vs_at, checked, worst_box, sum_box / checked, worst_at, sum_at / checked);
    // Measured: atBox - at() at most 0.031 (at() errs by up to 0.029 on the points checked);
    // atBox's own error at most 0.024, mean 0.0030 (at(): 0.0051). Every point against at()
    // within the band the decisions are tested with, the checked ones against the exact sum.
    EXPECT_LT(worst_vs_at, 0.05);
    EXPECT_LT(worst_box, 0.05);
    EXPECT_LT(sum_box, sum_at * 1.1 + 1e-3 * checked);
}

// The bricks' shared samples (solid/brick_samples.h), Sponza on a grid whose sides are not
// multiples of 8: every brick box's corners and middle are found, a halved box's corners are
// not; a value does not depend on which point asked first (two stores asked in opposite orders
// agree bit for bit); each is w - c at its lifted point within the fast winding numbers'
// accuracy of the exact double sum (and of at()).
TEST(SolidWinding, BrickSamplesAreTheBoxesPointsAndMatchTheExactSum) {
    const SponzaOnGrid sponza(100);
    const ValidatedMesh& validated = sponza.validated;
    const GridSpec& grid = sponza.grid;
    ASSERT_TRUE(grid.dims[1] % 8 != 0 && grid.dims[2] % 8 != 0) << "the test wants bricks cut by the grid's end";
    const solid::FastWinding fast(validated, grid, 2.0);
    const solid::RayCrossings rays(validated, grid);
    const solid::TreeLessCrossings less(fast);
    const solid::BrickSamples forward(less, rays, grid.dims), backward(less, rays, grid.dims);
    using Int3 = std::array<std::int32_t, 3>;
    std::vector<Int3> points;  // every brick box's corners and middle (repeated: shared corners)
    std::vector<Int3> halved;  // corners of a halved box that are neither
    for (int bx = 0; 8 * bx < grid.dims[0]; ++bx)
        for (int by = 0; 8 * by < grid.dims[1]; ++by)
            for (int bz = 0; 8 * bz < grid.dims[2]; ++bz) {
                Int3 lo{8 * bx, 8 * by, 8 * bz}, top;
                bool wide = true;
                for (int d = 0; d < 3; ++d) {
                    top[d] = lo[d] + 8 < grid.dims[d] ? lo[d] + 8 : grid.dims[d] - 1;
                    wide = wide && top[d] - lo[d] >= 2;
                }
                for (int c = 0; c < 8; ++c)
                    points.push_back({c & 4 ? top[0] : lo[0], c & 2 ? top[1] : lo[1], c & 1 ? top[2] : lo[2]});
                const Int3 middle{(lo[0] + top[0]) / 2, (lo[1] + top[1]) / 2, (lo[2] + top[2]) / 2};
                if (wide) points.push_back(middle);
                if (top[0] - lo[0] == 8) halved.push_back({middle[0], lo[1], lo[2]});
                if (top[0] - lo[0] == 8 && top[1] - lo[1] == 8) halved.push_back({lo[0] + 2, lo[1] + 2, lo[2] + 2});
            }
    std::vector<double> first(points.size()), second(points.size());
    for (std::size_t n = 0; n < points.size(); ++n) ASSERT_TRUE(forward.find(points[n], first[n]));
    for (std::size_t n = points.size(); n-- > 0;) ASSERT_TRUE(backward.find(points[n], second[n]));
    for (std::size_t n = 0; n < points.size(); ++n) ASSERT_EQ(first[n], second[n]) << n;  // NaN fails too
    for (const Int3& p : halved) {
        double v;
        EXPECT_FALSE(forward.find(p, v)) << p[0] << "," << p[1] << "," << p[2];
    }
    EXPECT_EQ(forward.evaluations(), backward.evaluations());

    double worst_exact = 0, worst_at = 0, sum_exact = 0;
    int checked = 0;
    std::vector<solid::RayCrossings::Crossing> column;
    for (std::size_t n = 0; n < points.size(); n += 41) {
        const Int3& p = points[n];
        rays.column(p[0], p[1], column);
        const double h = solid::sampleHeight(column, p[2] + 0.5);
        const solid::Vec3 q{p[0] + 0.5, p[1] + 0.5, h};
        const double exact = sponza.exactWinding(q);
        const int below = solid::crossingsBelow(column, h);
        worst_exact = std::max(worst_exact, std::fabs(first[n] - (exact - below)));
        worst_at = std::max(worst_at, std::fabs(first[n] - (fast.at(q) - below)));
        sum_exact += std::fabs(first[n] - (exact - below));
        ++checked;
    }
    std::printf(
        "brick samples: %zu points; against the exact sum over %d: max %.3g mean %.3g; against at(): max %.3g\n",
        points.size(), checked, worst_exact, sum_exact / checked, worst_at);
    // Measured: against the exact sum max 0.029, mean 0.005 (at() itself errs as much there);
    // against at() max 0.004. The bounds are the band the decisions are tested with.
    EXPECT_GT(checked, 100);
    EXPECT_LT(worst_exact, 0.05);
    EXPECT_LT(worst_at, 0.05);
}

// The bricks' shared samples asked by four threads at once, each in its own order, against a
// store asked by one thread: the same points found, the same values bit for bit, the same
// evaluations (a block two threads evaluated at once is kept once). Sponza at 192: a hundred
// blocks and more, so that threads meet on blocks and rows being made (run under the
// sanitizers, the lazily made table's races).
TEST(SolidWinding, BrickSamplesAskedByManyThreadsEqualOneThreads) {
    const SponzaOnGrid sponza(192);
    const ValidatedMesh& validated = sponza.validated;
    const GridSpec& grid = sponza.grid;
    const solid::FastWinding fast(validated, grid, 2.0);
    const solid::RayCrossings rays(validated, grid);
    using Int3 = std::array<std::int32_t, 3>;
    // Every corner and middle coordinate is a multiple of 4 or among the last 8 voxels.
    std::array<std::vector<std::int32_t>, 3> axis;
    for (int d = 0; d < 3; ++d)
        for (std::int32_t c = 0; c < grid.dims[std::size_t(d)]; ++c)
            if (c % 4 == 0 || c >= grid.dims[std::size_t(d)] - 8) axis[std::size_t(d)].push_back(c);
    std::vector<Int3> candidates;
    for (const std::int32_t x : axis[0])
        for (const std::int32_t y : axis[1])
            for (const std::int32_t z : axis[2]) candidates.push_back({x, y, z});
    const solid::TreeLessCrossings less(fast);
    const solid::BrickSamples alone(less, rays, grid.dims), shared(less, rays, grid.dims);
    std::vector<double> expected(candidates.size(), NAN);
    std::vector<char> expected_found(candidates.size());
    for (std::size_t n = 0; n < candidates.size(); ++n) expected_found[n] = alone.find(candidates[n], expected[n]);
    constexpr int kThreads = 4;
    std::vector<std::vector<double>> values(kThreads, std::vector<double>(candidates.size(), NAN));
    std::vector<std::vector<char>> found(kThreads, std::vector<char>(candidates.size()));
    std::vector<std::thread> threads;
    for (int t = 0; t < kThreads; ++t)
        threads.emplace_back([&, t] {
            std::vector<std::size_t> order(candidates.size());
            for (std::size_t n = 0; n < order.size(); ++n) order[n] = n;
            std::shuffle(order.begin(), order.end(), std::mt19937(unsigned(t)));
            for (const std::size_t n : order)
                found[std::size_t(t)][n] = shared.find(candidates[n], values[std::size_t(t)][n]);
        });
    for (std::thread& t : threads) t.join();
    std::size_t points = 0;
    for (std::size_t n = 0; n < candidates.size(); ++n) {
        points += expected_found[n] != 0;
        for (int t = 0; t < kThreads; ++t) {
            ASSERT_EQ(found[std::size_t(t)][n], expected_found[n]) << n;
            if (expected_found[n]) {
                ASSERT_EQ(values[std::size_t(t)][n], expected[n]) << n << " thread " << t;  // NaN fails too
            }
        }
    }
    EXPECT_GT(points, 5000u);
    EXPECT_EQ(shared.evaluations(), alone.evaluations());
}

// An open mesh's solid voxels and counts on one thread and on two (the bricks' shared
// samples made by whichever thread comes first, the kept ray columns per thread).
TEST(SolidWinding, OpenMeshVoxelsDoNotDependOnTheThreads) {
    const test::TestMesh mesh = test::loadTestMesh(test::meshPath("sponza_crytek_262k_vcolor.ply.gz"));
    VoxelizeOptions one;
    one.mode = Mode::Solid;
    one.grid.resolution = 96;
    one.threads = 1;
    VoxelizeOptions two = one;
    two.threads = 2;
    const VoxelizeResult a = voxelize(mesh.view(), one), b = voxelize(mesh.view(), two);
    ASSERT_EQ(a.stats.solid->evaluation, "fast winding numbers");
    EXPECT_GT(a.stats.solid->interpolated_voxels, 0u);
    EXPECT_EQ(a.occupancy, b.occupancy);
    EXPECT_EQ(a.stats.solid->point_evaluations, b.stats.solid->point_evaluations);
    EXPECT_EQ(a.stats.solid->interpolated_voxels, b.stats.solid->interpolated_voxels);
}

// Calls one after another on one thread (what a thread keeps from brick to brick, the rays'
// columns of its recent bricks, belongs to the call): two cups open at the top on the same
// grid, whose bottoms cross the same columns at two heights inside one layer of bricks, and
// the first again. Each against the exact winding number, and the repeated call equal to the
// first in its voxels and its counts. Both bottoms lie between the bricks' lattice planes and
// their middles, where no sample of a brick box reads the rays: a call that counted the other
// cup's crossings would interpolate w - c smoothly across the band between the bottoms and
// decide its voxels off by one (with the windows kept per thread across calls and the call
// left out of their key, 1352 voxels of the second call were wrong).
TEST(SolidWinding, EachCallReadsItsOwnMeshsRays) {
    // In voxels of 1/16: the cup spans 3.2 .. 28.8 in x and y, its rim at z 56, its bottom at
    // `bottom` (17.2 or 19.6, between the planes 16 and 20); specks stretch the bounds to 32 ×
    // 32 × 64 voxels.
    auto cup = [](float bottom) {
        std::vector<float> positions;
        std::vector<std::uint32_t> triangles;
        auto polygon = [&](const std::vector<std::array<float, 3>>& corners) {
            const auto base = std::uint32_t(positions.size() / 3);
            for (const auto& c : corners)
                for (const float x : c) positions.push_back(x / 16);
            for (std::uint32_t k = 1; k + 1 < corners.size(); ++k)
                triangles.insert(triangles.end(), {base, base + k, base + k + 1});
        };
        const float a = 3.2f, b = 28.8f, lo = bottom, hi = 56;  // faces outward
        polygon({{a, a, lo}, {a, b, lo}, {b, b, lo}, {b, a, lo}});
        polygon({{a, a, lo}, {b, a, lo}, {b, a, hi}, {a, a, hi}});
        polygon({{a, b, lo}, {a, b, hi}, {b, b, hi}, {b, b, lo}});
        polygon({{a, a, lo}, {a, a, hi}, {a, b, hi}, {a, b, lo}});
        polygon({{b, a, lo}, {b, b, lo}, {b, b, hi}, {b, a, hi}});
        polygon({{0, 0, 0}, {0.16f, 0, 0}, {0, 0.16f, 0}});
        polygon({{32, 32, 64}, {31.84f, 32, 64}, {32, 31.84f, 64}});
        return std::make_pair(positions, triangles);
    };
    const float low = 17.2f, high = 19.6f;
    std::vector<VoxelizeResult> results;
    for (const float bottom : {low, high, low}) {
        const auto [positions, triangles] = cup(bottom);
        VoxelizeOptions options;
        options.mode = Mode::Solid;
        options.threads = 1;
        options.grid.resolution = 64;
        VoxelizeOptions surface_options = options;
        surface_options.mode = Mode::Conservative;
        const VoxelizeResult solid = voxelize(test::viewOf(positions, triangles), options);
        const VoxelizeResult surface = voxelize(test::viewOf(positions, triangles), surface_options);
        ASSERT_EQ(solid.stats.solid->evaluation, "fast winding numbers");
        ASSERT_EQ(solid.grid.dims, (std::array<std::int32_t, 3>{32, 32, 64}));
        const VoxelTriangles exact(positions, triangles, solid.grid);
        // `band`: the voxels checked whose centre lies between the two bottoms, inside the
        // cup's walls (those a call reading the other cup's crossings would miscount).
        int inside = 0, outside = 0, wrong = 0, band = 0;
        for (int i = 0; i < solid.grid.dims[0]; ++i)
            for (int j = 0; j < solid.grid.dims[1]; ++j)
                for (int k = 0; k < solid.grid.dims[2]; ++k) {
                    if (surface.occupancy.test(i, j, k)) continue;
                    const solid::Vec3 q{i + 0.5, j + 0.5, k + 0.5};
                    const double w = exact.winding(q);
                    if (std::fabs(w - 0.5) < 0.05) continue;
                    ++(w >= 0.5 ? inside : outside);
                    band += q[0] > 3.2 && q[0] < 28.8 && q[1] > 3.2 && q[1] < 28.8 && q[2] > low && q[2] < high;
                    wrong += solid.occupancy.test(i, j, k) != (w >= 0.5);
                }
        EXPECT_GT(inside, 10000) << bottom;
        EXPECT_GT(outside, 10000) << bottom;
        EXPECT_GT(band, 500) << bottom;
        EXPECT_EQ(wrong, 0) << bottom;
        results.push_back(solid);
    }
    const SolidStats &first = *results[0].stats.solid, &again = *results[2].stats.solid;
    EXPECT_EQ(again.point_evaluations, first.point_evaluations);
    EXPECT_EQ(again.interpolated_voxels, first.interpolated_voxels);
    EXPECT_EQ(results[2].stats.voxel_count, results[0].stats.voxel_count);
}

// An open room (no roof, a few large triangles) with small open quads floating in and around
// it, so that most bricks are decided from the interpolated smooth part of the winding
// number: every voxel outside the surface against the exact sum of the triangles' solid
// angles (those within 0.05 of 0.5 left out). The Python tests do this on more meshes; this
// one runs the open-mesh path under the sanitizers too.
TEST(SolidWinding, OpenRoomMatchesTheExactWindingNumber) {
    std::vector<float> positions;
    std::vector<std::uint32_t> triangles;
    auto quad = [&](const std::array<std::array<double, 3>, 4>& corners) {
        const auto base = std::uint32_t(positions.size() / 3);
        for (const auto& c : corners)
            for (double x : c) positions.push_back(float(x));
        triangles.insert(triangles.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    };
    // The room [0, 4] x [0, 3] x [0, 2], faces outward, the top left open.
    quad({{{0, 0, 0}, {0, 3, 0}, {4, 3, 0}, {4, 0, 0}}});
    quad({{{0, 0, 0}, {4, 0, 0}, {4, 0, 2}, {0, 0, 2}}});
    quad({{{0, 3, 0}, {0, 3, 2}, {4, 3, 2}, {4, 3, 0}}});
    quad({{{0, 0, 0}, {0, 0, 2}, {0, 3, 2}, {0, 3, 0}}});
    quad({{{4, 0, 0}, {4, 3, 0}, {4, 3, 2}, {4, 0, 2}}});
    std::mt19937 rng(4);
    std::uniform_real_distribution<double> x(-0.5, 4.5), y(-0.5, 3.5), z(0.2, 2.6), size(0.05, 0.2), unit(-1.0, 1.0);
    for (int n = 0; n < 60; ++n) {
        const std::array<double, 3> c{x(rng), y(rng), z(rng)};
        std::array<double, 3> a{unit(rng), unit(rng), unit(rng)}, b{unit(rng), unit(rng), unit(rng)};
        const double s = size(rng);
        quad({{{c[0] - s * a[0], c[1] - s * a[1], c[2] - s * a[2]},
               {c[0] - s * b[0], c[1] - s * b[1], c[2] - s * b[2]},
               {c[0] + s * a[0], c[1] + s * a[1], c[2] + s * a[2]},
               {c[0] + s * b[0], c[1] + s * b[1], c[2] + s * b[2]}}});
    }
    const MeshView view = test::viewOf(positions, triangles);
    VoxelizeOptions options;
    options.mode = Mode::Solid;
    options.grid.resolution = 48;
    VoxelizeOptions surface_options = options;
    surface_options.mode = Mode::Conservative;
    const VoxelizeResult solid = voxelize(view, options);
    const VoxelizeResult surface = voxelize(view, surface_options);
    ASSERT_EQ(solid.stats.solid->evaluation, "fast winding numbers");
    EXPECT_GT(solid.stats.solid->interpolated_voxels, 10000u);  // the smooth part decided most
    const VoxelTriangles exact(positions, triangles, solid.grid);
    int inside = 0, outside = 0;
    const auto dims = solid.grid.dims;
    for (int i = 0; i < dims[0]; ++i)
        for (int j = 0; j < dims[1]; ++j)
            for (int k = 0; k < dims[2]; ++k) {
                if (surface.occupancy.test(i, j, k)) continue;
                const solid::Vec3 q{i + 0.5, j + 0.5, k + 0.5};
                const double w = exact.winding(q);
                if (std::fabs(w - 0.5) < 0.05) continue;
                ASSERT_EQ(solid.occupancy.test(i, j, k), w >= 0.5) << i << "," << j << "," << k << " w " << w;
                ++(w >= 0.5 ? inside : outside);
            }
    EXPECT_GT(inside, 1000);
    EXPECT_GT(outside, 1000);
}

// An open box of side 24 voxels, each face cut into 32 × 32 squares (10240 triangles), its top
// left open (128 open edges: the rule samples it from their sheets); `shift` moves it off the
// lattice of voxel columns, which with shift 0 its rim runs along: the columns through the rim
// pass through open edges, where the sheets' sum is undefined.
struct OpenBox {
    std::vector<float> positions;
    std::vector<std::uint32_t> triangles;
    GridOptions grid;
    explicit OpenBox(double shift) {
        constexpr int kCuts = 32;
        constexpr double kSide = 1.0;
        auto face = [&](const std::array<double, 3>& corner, const std::array<double, 3>& u,
                        const std::array<double, 3>& v) {
            const auto base = std::uint32_t(positions.size() / 3);
            for (int a = 0; a <= kCuts; ++a)
                for (int b = 0; b <= kCuts; ++b)
                    for (int k = 0; k < 3; ++k)
                        positions.push_back(float(corner[k] + (u[k] * a + v[k] * b) * kSide / kCuts));
            for (int a = 0; a < kCuts; ++a)
                for (int b = 0; b < kCuts; ++b) {
                    const std::uint32_t p = base + std::uint32_t(a * (kCuts + 1) + b);
                    triangles.insert(triangles.end(), {p, p + kCuts + 1, p + kCuts + 2, p, p + kCuts + 2, p + 1});
                }
        };
        face({0, 0, 0}, {0, 1, 0}, {1, 0, 0});  // the bottom, facing down
        face({0, 0, 0}, {1, 0, 0}, {0, 0, 1});  // y = 0
        face({0, 1, 0}, {0, 0, 1}, {1, 0, 0});  // y = 1
        face({0, 0, 0}, {0, 0, 1}, {0, 1, 0});  // x = 0
        face({1, 0, 0}, {0, 1, 0}, {0, 0, 1});  // x = 1
        // Voxels of 1/24: with shift 0 the sides' planes run through voxel centres (x and y
        // 2.5 and 26.5 voxels from the origin).
        grid.voxel_size = kSide / 24;
        const double at = -(2.5 + shift) * kSide / 24;
        grid.origin = std::array<double, 3>{at, at, at};
    }
    MeshView view() const { return test::viewOf(positions, triangles); }
};

// What solid::fillInside takes for a mesh on a grid: the solid options, the surface voxels,
// the validated mesh and its edge check.
struct InsideInputs {
    VoxelizeOptions options;
    VoxelizeResult surface;
    ValidatedMesh validated;
    solid::EdgeClosure closure;
    InsideInputs(const MeshView& view, const GridOptions& grid_options)
        : options(withGrid(grid_options)),
          surface(voxelize(view, options)),
          validated(validate(view)),
          closure(solid::checkEdges(validated, surface.grid)) {
        options.mode = Mode::Solid;
    }
    static VoxelizeOptions withGrid(const GridOptions& grid_options) {
        VoxelizeOptions options;
        options.grid = grid_options;
        return options;
    }
};

// The voxels off the surface (every `stride`-th along the grid's order) against the exact
// winding number (those within 0.05 of 0.5 left out), sampled from the sheets and from the tree.
void expectBothSamplingsExact(const MeshView& view, const GridOptions& grid_options, int stride) {
    const InsideInputs in(view, grid_options);
    const VoxelizeOptions& options = in.options;
    const VoxelizeResult& surface = in.surface;
    const ValidatedMesh& validated = in.validated;
    const solid::EdgeClosure& closure = in.closure;
    ASSERT_FALSE(closure.open_edges.empty());
    const VoxelTriangles exact(validated, surface.grid);
    const auto dims = surface.grid.dims;
    std::vector<double> windings;
    for (int i = 0; i < dims[0]; ++i)
        for (int j = 0; j < dims[1]; ++j)
            for (int k = 0; k < dims[2]; ++k) {
                const bool checked = windings.size() % std::size_t(stride) == 0 && !surface.occupancy.test(i, j, k);
                windings.push_back(checked ? exact.winding({i + 0.5, j + 0.5, k + 0.5}) : NAN);
            }
    for (const auto sampling : {solid::OpenSampling::Tree, solid::OpenSampling::Sheets}) {
        const bool sheets = sampling == solid::OpenSampling::Sheets;
        SCOPED_TRACE(sheets ? "sheets" : "tree");
        SolidStats stats;
        const SparseGrid inside = solid::fillInside(validated, surface.grid, surface.occupancy, options, closure,
                                                    nullptr, stats, nullptr, sampling);
        EXPECT_EQ(stats.evaluation, sheets ? "sheets of the open edges" : "fast winding numbers");
        int counted[2] = {0, 0};
        std::size_t n = 0;
        for (int i = 0; i < dims[0]; ++i)
            for (int j = 0; j < dims[1]; ++j)
                for (int k = 0; k < dims[2]; ++k) {
                    const double w = windings[n++];
                    if (std::isnan(w) || std::fabs(w - 0.5) < 0.05) continue;
                    ASSERT_EQ(inside.test(i, j, k), w >= 0.5) << i << "," << j << "," << k << " w " << w;
                    ++counted[w >= 0.5];
                }
        EXPECT_GT(counted[0], 500);
        EXPECT_GT(counted[1], 500);
    }
}

TEST(SolidWinding, SheetsAndTreeBothGiveTheExactWindingNumber) {
    const test::TestMesh bunny = test::loadTestMesh(test::meshPath("bunny_stanford_69k.ply"));
    const MeshView bunny_view = test::viewOf(bunny.positions, bunny.triangles);
    const ValidatedMesh validated = validate(bunny_view);
    GridOptions bunny_grid;
    bunny_grid.resolution = 32;
    {
        SCOPED_TRACE("bunny");
        const solid::EdgeClosure closure = solid::checkEdges(validated, makeGrid(validated.bounds, bunny_grid));
        EXPECT_TRUE(solid::bySheets(closure.open_edges.size(), validated.usable.size()));
        expectBothSamplingsExact(bunny_view, bunny_grid, 5);
    }
    for (const double shift : {0.0, 0.3}) {
        SCOPED_TRACE("open box, shift " + std::to_string(shift));
        const OpenBox box(shift);
        expectBothSamplingsExact(box.view(), box.grid, 1);
    }
}

// The sheets' sum at points of the open box's voxel columns against the exact w - c: off the
// rim every point by the sheets; on the lattice, the columns through the rim undefined (each
// counted beforehand), their points by the exact sum, or by the tree, built then, when the
// budget for the exact sum is 0; shifted off it, none.
TEST(SolidWinding, SheetsUndefinedOnTheRimTakeTheExactSumOrTheTree) {
    for (const double shift : {0.0, 0.3})
        for (const std::uint64_t exact_work : {std::numeric_limits<std::uint64_t>::max(), std::uint64_t(0)}) {
            SCOPED_TRACE("shift " + std::to_string(shift) + ", exact work " + std::to_string(exact_work));
            const OpenBox box(shift);
            const ValidatedMesh validated = validate(box.view());
            const GridSpec grid = makeGrid(validated.bounds, box.grid);
            const solid::EdgeClosure closure = solid::checkEdges(validated, grid);
            ASSERT_EQ(closure.open_edges.size(), 128u);
            const solid::GradientBound bound(closure.open_edges);
            const solid::SheetWinding sheets(validated, grid, bound, 2.0, exact_work);
            const solid::RayCrossings rays(validated, grid);
            const VoxelTriangles exact(validated, grid);
            std::vector<solid::RayCrossings::Crossing> column;
            double worst = 0;
            int points = 0, undefined_columns = 0;
            for (int i = 0; i < grid.dims[0]; i += 1)
                for (int j = 0; j < grid.dims[1]; j += 1) {
                    rays.column(i, j, column);
                    const std::uint64_t undefined_before = sheets.undefinedPoints();
                    // Heights off the surface: between the bottom (2.5 + shift) and the rim's
                    // height (26.5 + shift), and above it.
                    for (const double z : {9.25, 17.75, 29.25}) {
                        const solid::Vec3 q{i + 0.5, j + 0.5, z};
                        const int below = solid::crossingsBelow(column, z);
                        double less;
                        sheets.at(&q, &below, 1, false, &less);
                        worst = std::max(worst, std::fabs(less - (exact.winding(q) - below)));
                        ++points;
                    }
                    undefined_columns += sheets.undefinedPoints() > undefined_before;
                }
            EXPECT_GT(points, 2000);
            EXPECT_GE(sheets.undefinedColumns(), std::uint64_t(undefined_columns));
            if (shift == 0.0) {
                EXPECT_EQ(sheets.exactWhereUndefined(), exact_work > 0);
                EXPECT_GT(undefined_columns, 90);  // the rim, 4 sides of 24 voxels
                EXPECT_EQ(sheets.treeBuilt(), exact_work == 0);
                EXPECT_LT(worst, exact_work > 0 ? 1e-4 : 0.05);  // float sheets; the tree's accuracy
            } else {
                EXPECT_EQ(sheets.undefinedColumns(), 0u);
                EXPECT_EQ(sheets.undefinedPoints(), 0u);
                EXPECT_FALSE(sheets.treeBuilt());
                EXPECT_LT(worst, 1e-4);  // float sheets
            }
        }
}

// The solid voxels of open meshes sampled from the sheets are the same on one thread and on
// two: the bunny (no column through an open edge) and the open box on the lattice (its rim's
// columns undefined, taken by the exact sum or the tree as decided beforehand, not by which
// thread comes first).
TEST(SolidWinding, SheetsGiveTheSameVoxelsOnAnyNumberOfThreads) {
    const test::TestMesh bunny = test::loadTestMesh(test::meshPath("bunny_stanford_69k.ply"));
    GridOptions bunny_grid;
    bunny_grid.resolution = 64;
    const OpenBox box(0.0);
    const std::vector<std::pair<MeshView, GridOptions>> cases{
        {test::viewOf(bunny.positions, bunny.triangles), bunny_grid}, {box.view(), box.grid}};
    for (const auto& [view, grid_options] : cases) {
        const InsideInputs in(view, grid_options);
        auto insideOn = [&](int threads) {
            tbb::task_arena arena(threads);
            return arena.execute([&] {
                SolidStats stats;
                return solid::fillInside(in.validated, in.surface.grid, in.surface.occupancy, in.options, in.closure,
                                         nullptr, stats, nullptr, solid::OpenSampling::Sheets);
            });
        };
        const SparseGrid one = insideOn(1), two = insideOn(2);
        std::size_t inside = 0;
        const auto dims = in.surface.grid.dims;
        for (int i = 0; i < dims[0]; ++i)
            for (int j = 0; j < dims[1]; ++j)
                for (int k = 0; k < dims[2]; ++k) {
                    ASSERT_EQ(one.test(i, j, k), two.test(i, j, k)) << i << "," << j << "," << k;
                    inside += one.test(i, j, k);
                }
        EXPECT_GT(inside, 1000u);
    }
}

}  // namespace
}  // namespace hyvox
