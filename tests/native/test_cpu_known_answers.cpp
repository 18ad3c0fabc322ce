// SPDX-License-Identifier: GPL-3.0-or-later
// Hand-derived voxel sets (closed-box rule) for the cpu and reference methods: a unit cube,
// a box whose size is a multiple of the voxel size, triangles lying exactly on voxel
// planes (both sides marked), a triangle smaller than a voxel, one spanning and clipped by
// the grid; bad input; the oracle's touch tolerance itself.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "reference/reference_overlap.h"
#include "support/triangle_soup.h"
#include "support/voxel_checks.h"

namespace hyvox::test {
namespace {

const Method kMethods[] = {Method::Cpu, Method::Reference};

VoxelizeResult run(const TriangleSoup& soup, const GridOptions& grid, Mode mode, Method method) {
    VoxelizeOptions options;
    options.grid = grid;
    options.mode = mode;
    options.method = method;
    return voxelize(soup.view(), options);
}

// Voxels of `dims` whose closed box meets the surface of the voxel-space box [lo, hi]
// (integer corners): those meeting the closed box minus those strictly inside the open box.
VoxelList boxShell(const std::array<int, 3>& dims, const std::array<int, 3>& lo, const std::array<int, 3>& hi) {
    VoxelList out;
    for (int i = 0; i < dims[0]; ++i)
        for (int j = 0; j < dims[1]; ++j)
            for (int k = 0; k < dims[2]; ++k) {
                const int p[3] = {i, j, k};
                bool meets = true, strictly_inside = true;
                for (int a = 0; a < 3; ++a) {
                    meets &= p[a] + 1 >= lo[a] && p[a] <= hi[a];
                    strictly_inside &= p[a] > lo[a] && p[a] + 1 < hi[a];
                }
                if (meets && !strictly_inside) out.push_back({i, j, k});
            }
    return out;
}

TEST(KnownAnswers, UnitCubeMarksTheClosedBoxShell) {
    TriangleSoup cube;
    cube.addBox({0, 0, 0}, {1, 1, 1});
    GridOptions grid;
    grid.resolution = 4;  // voxel size 1/4: every face lies on a voxel plane
    grid.padding = 1;     // so the voxels outside each face are inside the grid
    const VoxelList expected = boxShell({6, 6, 6}, {1, 1, 1}, {5, 5, 5});
    ASSERT_EQ(expected.size(), 216u - 8u);
    for (Method method : kMethods) {
        const auto result = run(cube, grid, Mode::Conservative, method);
        EXPECT_EQ(result.grid.dims, (std::array<std::int32_t, 3>{6, 6, 6}));
        EXPECT_EQ(sortedVoxels(result), expected) << toString(method);
    }
}

TEST(KnownAnswers, BoxWithSizeAMultipleOfTheVoxelSize) {
    TriangleSoup box;
    box.addBox({0, 0, 0}, {3, 2, 5});
    GridOptions grid;
    grid.voxel_size = 0.5;
    grid.padding = 1;
    const VoxelList expected = boxShell({8, 6, 12}, {1, 1, 1}, {7, 5, 11});
    for (Method method : kMethods) {
        const auto result = run(box, grid, Mode::Conservative, method);
        ASSERT_EQ(result.grid.dims, (std::array<std::int32_t, 3>{8, 6, 12}));
        EXPECT_EQ(sortedVoxels(result), expected) << toString(method);
    }
}

// A right triangle with legs 4 along (u, v) = the two axes after `w`, lying exactly on the
// voxel plane w = 2: the voxel layers w = 1 and w = 2 both touch it.
TriangleSoup triangleOnPlane(int w, double size) {
    const int u = (w + 1) % 3, v = (w + 2) % 3;
    std::array<double, 3> a{}, b{}, c{};
    a[w] = b[w] = c[w] = 2 * size;
    b[u] = 4 * size;
    c[v] = 4 * size;
    TriangleSoup soup;
    soup.add(a, b, c);
    return soup;
}

VoxelList onPlaneExpected(int w, int max_sum) {
    const int u = (w + 1) % 3, v = (w + 2) % 3;
    VoxelList out;
    for (int pu = 0; pu < 4; ++pu)
        for (int pv = 0; pv < 4; ++pv)
            if (pu + pv <= max_sum)
                for (int pw : {1, 2}) {
                    std::array<std::int32_t, 3> p{};
                    p[u] = pu;
                    p[v] = pv;
                    p[w] = pw;
                    out.push_back(p);
                }
    std::sort(out.begin(), out.end());
    return out;
}

TEST(KnownAnswers, TriangleOnVoxelFacesMarksBothSides) {
    for (double size : {1.0, 0.125}) {  // exact in binary: the plane stays exactly on voxel faces
        for (int w = 0; w < 3; ++w) {
            const TriangleSoup soup = triangleOnPlane(w, size);
            for (Method method : kMethods) {
                // Conservative: column (u,v) meets the triangle u,v >= 0, u+v <= 4 iff u+v <= 4.
                EXPECT_EQ(sortedVoxels(run(soup, unitGrid(4, size), Mode::Conservative, method)), onPlaneExpected(w, 4))
                    << "axis " << w << " " << toString(method);
                // Thin: the column centre's diamond reaches u+v = 4 iff u+v+1 - 1/2 <= 4.
                EXPECT_EQ(sortedVoxels(run(soup, unitGrid(4, size), Mode::Thin, method)), onPlaneExpected(w, 3))
                    << "axis " << w << " " << toString(method);
            }
        }
    }
}

TEST(KnownAnswers, TriangleSmallerThanAVoxel) {
    TriangleSoup inside;  // well inside voxel (2,1,3)
    inside.add({2.3, 1.4, 3.5}, {2.6, 1.45, 3.55}, {2.4, 1.7, 3.4});
    TriangleSoup at_corner;  // a vertex exactly on the corner (2,2,2) shared by 8 closed boxes
    at_corner.add({2, 2, 2}, {2.3, 2.1, 2.05}, {2.1, 2.3, 2.2});
    VoxelList corner_expected;
    for (int i : {1, 2})
        for (int j : {1, 2})
            for (int k : {1, 2}) corner_expected.push_back({i, j, k});
    for (Method method : kMethods) {
        EXPECT_EQ(sortedVoxels(run(inside, unitGrid(5), Mode::Conservative, method)), (VoxelList{{2, 1, 3}}));
        // Near the voxel centre it also meets the inscribed diamond: thin marks it too.
        EXPECT_EQ(sortedVoxels(run(inside, unitGrid(5), Mode::Thin, method)), (VoxelList{{2, 1, 3}}));
        EXPECT_EQ(sortedVoxels(run(at_corner, unitGrid(5), Mode::Conservative, method)), corner_expected);
    }
}

TEST(KnownAnswers, TriangleSpanningAndClippedByTheGrid) {
    // A huge triangle in the plane z = 1.5 (voxel units); the grid (8^3) clips it.
    TriangleSoup flat;
    flat.add({-100, -100, 1.5}, {300, -100, 1.5}, {-100, 300, 1.5});
    VoxelList layer;
    for (int i = 0; i < 8; ++i)
        for (int j = 0; j < 8; ++j) layer.push_back({i, j, 1});
    for (Method method : kMethods)
        for (Mode mode : {Mode::Conservative, Mode::Thin})
            EXPECT_EQ(sortedVoxels(run(flat, unitGrid(8), mode, method)), layer) << toString(method);

    // A slanted one through the whole grid: the plane x + y + z = 12.5 crosses every column;
    // conservative marks exactly the voxels whose corner sums straddle it.
    TriangleSoup slanted;
    slanted.add({12.5 + 200, -100, -100}, {-100, 12.5 + 200, -100}, {-100, -100, 12.5 + 200});
    VoxelList expected;
    for (int i = 0; i < 8; ++i)
        for (int j = 0; j < 8; ++j)
            for (int k = 0; k < 8; ++k)
                if (i + j + k <= 12.5 && i + j + k + 3 >= 12.5) expected.push_back({i, j, k});
    for (Method method : kMethods)
        EXPECT_EQ(sortedVoxels(run(slanted, unitGrid(8), Mode::Conservative, method)), expected) << toString(method);

    // Triangles far beyond the grid on either side of every axis (past int range in voxel
    // units) add nothing: the candidate ranges are clamped before any int conversion.
    TriangleSoup far = flat;
    for (double d : {-1e12, 1e12}) {
        far.add({d, 0, 0}, {d, 1, 0}, {d, 0, 1});
        far.add({0, d, 0}, {1, d, 0}, {0, d, 1});
        far.add({0, 0, d}, {1, 0, d}, {0, 1, d});
    }
    for (Method method : kMethods)
        for (Mode mode : {Mode::Conservative, Mode::Thin})
            EXPECT_EQ(sortedVoxels(run(far, unitGrid(8), mode, method)), layer) << toString(method);
}

TEST(KnownAnswers, BadInputGivesClearErrors) {
    for (Method method : kMethods) {
        VoxelizeOptions options;
        options.method = method;
        TriangleSoup nan_mesh;
        nan_mesh.add({0, 0, 0}, {1, 0, 0}, {0, std::numeric_limits<double>::quiet_NaN(), 0});
        try {
            voxelize(nan_mesh.view(), options);
            ADD_FAILURE() << "NaN accepted";
        } catch (const InvalidInput& e) {
            EXPECT_NE(std::string(e.what()).find("NaN"), std::string::npos) << e.what();
        }
        TriangleSoup inf_mesh;
        inf_mesh.add({0, 0, 0}, {1, 0, 0}, {0, std::numeric_limits<double>::infinity(), 0});
        EXPECT_THROW(voxelize(inf_mesh.view(), options), InvalidInput);

        TriangleSoup degenerate;  // collinear, and a repeated vertex
        degenerate.add({0, 0, 0}, {1, 1, 1}, {2, 2, 2});
        degenerate.add({0, 0, 0}, {0, 0, 0}, {1, 0, 0});
        try {
            voxelize(degenerate.view(), options);
            ADD_FAILURE() << "all-degenerate mesh accepted";
        } catch (const InvalidInput& e) {
            EXPECT_NE(std::string(e.what()).find("degenerate"), std::string::npos) << e.what();
        }

        // A degenerate triangle beside a good one is skipped and counted, never marks voxels.
        TriangleSoup good, mixed;
        good.add({0.2, 0.2, 0.2}, {3.7, 0.4, 1.1}, {1.3, 3.6, 2.9});
        mixed = good;
        mixed.add({0, 0, 0}, {2, 2, 2}, {4, 4, 4});
        options.grid = unitGrid(4);
        const auto a = voxelize(good.view(), options);
        const auto b = voxelize(mixed.view(), options);
        EXPECT_EQ(b.stats.triangles_degenerate, 1u);
        EXPECT_EQ(b.stats.triangles_used, 1u);
        EXPECT_EQ(sortedVoxels(a), sortedVoxels(b));

        std::vector<float> positions{0, 0, 0, 1, 0, 0, 0, 1, 0};
        std::vector<std::uint32_t> bad_index{0, 1, 7};
        MeshView view{positions.data(), 3, bad_index.data(), 1};
        EXPECT_THROW(voxelize(view, options), InvalidInput);
    }
}

TEST(KnownAnswers, TouchToleranceSeparatesTouchesFromOverlaps) {
    // Touches voxel (0,0,0) exactly at its corner (1,1,1) from outside.
    const reference::Triangle corner_touch{{{1, 1, 1}, {2, 1.5, 1.2}, {1.3, 2, 1.7}}};
    EXPECT_TRUE(reference::overlaps(corner_touch, {0, 0, 0}, Mode::Conservative));
    EXPECT_TRUE(overlapWithin(corner_touch, {0, 0, 0}, Mode::Conservative, 1e-5).isTouch());
    // 2e-5 away: not even the grown box meets it.
    const reference::Triangle near{{{1 + 2e-5, 1, 1}, {2, 1.5, 1.2}, {1.3, 2, 1.7}}};
    EXPECT_FALSE(overlapWithin(near, {0, 0, 0}, Mode::Conservative, 1e-5).grown);
    // Clearly through the voxel: overlaps even the shrunk box, not a touch.
    const reference::Triangle through{{{-1, 0.5, -1}, {2, 0.5, -1}, {0.5, 0.5, 2}}};
    EXPECT_TRUE(overlapWithin(through, {0, 0, 0}, Mode::Conservative, 1e-5).shrunk);
    EXPECT_TRUE(overlapWithin(through, {0, 0, 0}, Mode::Thin, 1e-5).shrunk);
    // Thin: a plane exactly through the inscribed octahedron's top vertex (z = 1) touches it.
    const reference::Triangle top{{{-5, -5, 1}, {5, -5, 1}, {0, 5, 1}}};
    EXPECT_TRUE(overlapWithin(top, {0, 0, 0}, Mode::Thin, 1e-5).isTouch());
}

}  // namespace
}  // namespace hyvox::test
