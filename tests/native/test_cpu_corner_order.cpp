// SPDX-License-Identifier: GPL-3.0-or-later
// A triangle's voxels must not depend on which of its corners comes first, nor on its
// winding: validate()'s zero-area rule and the normal every double method takes come from
// the corners' values alone (core/triangle_normal.h). Near-degenerate triangles are where
// the order could show: the fuzz findings' needles and slivers, and generated needles, caps
// and slivers from 1e-30 to 1e30. Each is voxelized in its 6 corner orders (3 rotations,
// each reflected) by the cpu method and the reference, conservative and thin; every order
// must give the same voxels as the first (or every order none: a triangle judged zero-area
// in one order is judged so in all), and the cpu method must match the reference up to
// touches. (Not expectMatchesOracle's "few touches": the fuzzed thin sliver starts at a grid
// corner and runs in the plane y = z through voxel edges, 29 touches in conservative mode.)
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "hyvox/errors.h"
#include "hyvox/voxelize.h"
#include "support/mesh_arrays.h"
#include "support/voxel_checks.h"

namespace hyvox::test {
namespace {

using Corners = std::array<std::array<float, 3>, 3>;

struct Case {
    std::string name;
    Corners corners;
};

// The corner orders: rotations of (0, 1, 2) and of its reflection (0, 2, 1).
const std::array<std::array<std::uint32_t, 3>, 6> kOrders{
    {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}, {0, 2, 1}, {2, 1, 0}, {1, 0, 2}}};

std::vector<Case> nearDegenerateTriangles() {
    std::vector<Case> cases{
        {"fuzz_needle_near_1e-37",
         {{{-1.41794e-37f, -1.917669e-37f, -1.917669e-37f},
           {-1.924353e-37f, 1.1985432e-38f, 0.0f},
           {-2.5045195e+33f, -2.5045195e+33f, -2.5045195e+33f}}}},
        {"fuzz_thin_sliver_1e-19_wide",
         {{{0.0f, 4.9223826e-38f, -1.0652918e-37f},
           {1.41499e-17f, 8.843688e-18f, 8.843688e-18f},
           {-1.912195e-37f, -1.9029754e-37f, 0.0f}}}},
        {"fuzz_sliver_beside_a_diagonal",
         {{{8.85928915e-41f, 0.0f, -1.91017832e-37f},
           {-2.50451951e+33f, 2.11894795e-33f, -2.50448284e+33f},
           {-9.40395481e-38f, 2.1019477e-44f, 8.0f}}}},
    };
    // Generated at several scales: needles (two corners a few ulps apart), caps (the middle
    // corner a few ulps off the segment between the others) and slivers (one corner a few
    // ulps off the far corner's line), in general position so they cross many voxels.
    std::mt19937 random(16);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    std::uniform_int_distribution<int> ulps(1, 4);
    const auto nudge = [&](float x) {
        for (int i = ulps(random); i > 0; --i) x = std::nextafter(x, unit(random) > 0 ? 1e38f : -1e38f);
        return x;
    };
    for (float scale : {1e-30f, 1e-3f, 1.0f, 1e30f})
        for (int kind = 0; kind < 3; ++kind)
            for (int i = 0; i < 2; ++i) {
                std::array<float, 3> a, b, c;
                for (int axis = 0; axis < 3; ++axis) {
                    a[axis] = scale * unit(random);
                    b[axis] = scale * unit(random);
                    if (kind == 0) c[axis] = nudge(b[axis]);                                // needle
                    if (kind == 1) c[axis] = nudge(0.5f * a[axis] + 0.5f * b[axis]);        // cap
                    if (kind == 2) c[axis] = nudge(b[axis] + 1e-6f * (b[axis] - a[axis]));  // sliver
                }
                const char* kinds[] = {"needle", "cap", "sliver"};
                char name[64];
                std::snprintf(name, sizeof name, "%s_%g_%d", kinds[kind], double(scale), i);
                cases.push_back({name, {a, b, c}});
            }
    return cases;
}

// The voxels of one order, or none (the triangle judged zero-area: validate() refuses a mesh
// of it alone).
struct OrderRun {
    bool degenerate = false;
    VoxelizeResult result;
};

OrderRun voxelizeInOrder(const Corners& corners, const std::array<std::uint32_t, 3>& order, Method method, Mode mode) {
    std::vector<float> positions;
    for (const auto& corner : corners) positions.insert(positions.end(), corner.begin(), corner.end());
    const std::vector<std::uint32_t> triangles(order.begin(), order.end());
    VoxelizeOptions options;
    options.grid.resolution = 40;
    options.grid.padding = 1;
    options.method = method;
    options.mode = mode;
    options.threads = 1;
    OrderRun run;
    try {
        run.result = voxelize(viewOf(positions, triangles), options);
    } catch (const InvalidInput&) {
        run.degenerate = true;
    }
    return run;
}

TEST(CornerOrder, NearDegenerateTrianglesGiveTheSameVoxelsInEveryOrder) {
    int kept = 0;
    for (const Case& c : nearDegenerateTriangles())
        for (Mode mode : {Mode::Conservative, Mode::Thin}) {
            SCOPED_TRACE(c.name + " " + toString(mode));
            OrderRun first[2];
            const Method methods[2] = {Method::Cpu, Method::Reference};
            for (int m = 0; m < 2; ++m) {
                first[m] = voxelizeInOrder(c.corners, kOrders[0], methods[m], mode);
                for (std::size_t o = 1; o < kOrders.size(); ++o) {
                    SCOPED_TRACE(std::string(toString(methods[m])) + " order " + std::to_string(o));
                    const OrderRun other = voxelizeInOrder(c.corners, kOrders[o], methods[m], mode);
                    ASSERT_EQ(other.degenerate, first[m].degenerate);
                    if (!other.degenerate) {
                        EXPECT_TRUE(other.result.occupancy == first[m].result.occupancy);
                    }
                }
            }
            ASSERT_EQ(first[0].degenerate, first[1].degenerate);
            if (first[0].degenerate) continue;
            kept += mode == Mode::Conservative;
            std::vector<float> positions;
            for (const auto& corner : c.corners) positions.insert(positions.end(), corner.begin(), corner.end());
            const std::vector<std::uint32_t> triangles{0, 1, 2};
            const Comparison cmp = compareResults(viewOf(positions, triangles), mode, first[0].result, first[1].result);
            std::printf("[ compare  ] %s %s: %s\n", c.name.c_str(), toString(mode), cmp.summary().c_str());
            EXPECT_TRUE(cmp.unexplained.empty()) << cmp.summary();
        }
    EXPECT_GE(kept, 20);  // most of them are true triangles in double
}

}  // namespace
}  // namespace hyvox::test
