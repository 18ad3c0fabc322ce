// SPDX-License-Identifier: GPL-3.0-or-later
// The cpu method's slab sweep (attributes/sweep_cells.h) against box-by-box clipping
// (clipTriangleToVoxel, the reference method's): the same voxels, the same areas and
// centroids to rounding, areas that add up to the triangle's, and touches through voxel
// corners found on every side.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>

#include "attributes/clip_to_voxel.h"
#include "attributes/sweep_triangle.h"

namespace {

using hyvox::attributes::ClippedPiece;
using hyvox::attributes::Point;
using hyvox::attributes::TriangleFrame;
using Corners = std::array<Point, 3>;
using hyvox::attributes::Voxel;
using Pieces = std::map<Voxel, ClippedPiece>;

// Every piece of the triangle in the voxels of [lo, hi]³, by the sweep (sweepTriangle: the
// slab sweep along the dominant axis last, inner columns measured without cuts); `inner`
// counts the pieces of inner columns.
Pieces sweep(const Corners& corners, int lo, int hi, std::uint64_t* inner = nullptr) {
    const TriangleFrame frame(corners);
    Pieces pieces;
    const std::uint64_t from_inner =
        hyvox::attributes::sweepTriangle(corners, frame, {lo, lo, lo}, {hi, hi, hi}, hyvox::attributes::EveryVoxel{},
                                         [&](const Voxel& voxel, const ClippedPiece& piece) {
                                             EXPECT_TRUE(pieces.emplace(voxel, piece).second) << "voxel visited twice";
                                         });
    if (inner) *inner += from_inner;
    return pieces;
}

// The same by clipping the triangle to every box of [lo, hi]³ (grown by `margin`).
Pieces clipBoxes(const Corners& corners, int lo, int hi, double margin) {
    const TriangleFrame frame(corners);
    Pieces pieces;
    // Only boxes near the triangle's bounding box can meet it.
    Voxel from, to;
    for (std::size_t d = 0; d < 3; ++d) {
        const double low = std::min({corners[0][d], corners[1][d], corners[2][d]});
        const double high = std::max({corners[0][d], corners[1][d], corners[2][d]});
        from[d] = std::max(lo, int(std::floor(low)) - 1);
        to[d] = std::min(hi, int(std::floor(high)) + 1);
    }
    for (int i = from[0]; i <= to[0]; ++i)
        for (int j = from[1]; j <= to[1]; ++j)
            for (int k = from[2]; k <= to[2]; ++k) {
                ClippedPiece piece;
                if (clipTriangleToVoxel(corners, {i, j, k}, frame, piece, margin))
                    pieces.emplace(Voxel{i, j, k}, piece);
            }
    return pieces;
}

double triangleArea(const Corners& c) {
    const Point u{c[1][0] - c[0][0], c[1][1] - c[0][1], c[1][2] - c[0][2]};
    const Point v{c[2][0] - c[0][0], c[2][1] - c[0][1], c[2][2] - c[0][2]};
    const Point n{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    return 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

void expectSamePiece(const ClippedPiece& got, const ClippedPiece& expected, const Voxel& v) {
    EXPECT_NEAR(got.area, expected.area, 1e-12) << v[0] << " " << v[1] << " " << v[2];
    for (std::size_t d = 0; d < 3; ++d)
        EXPECT_NEAR(got.centroid[d], expected.centroid[d], 1e-9) << v[0] << " " << v[1] << " " << v[2];
}

// A triangle of corners spread up to a random `size` around a random centre.
Corners randomTriangle(std::mt19937& random, std::uniform_real_distribution<double>& coordinate,
                       std::uniform_real_distribution<double>& size) {
    const Point centre{coordinate(random), coordinate(random), coordinate(random)};
    const double scale = size(random);
    std::uniform_real_distribution<double> offset(-scale, scale);
    Corners corners;
    for (Point& corner : corners)
        for (std::size_t d = 0; d < 3; ++d) corner[d] = centre[d] + offset(random);
    return corners;
}

// The sweep over [lo, hi) finds exactly box clipping's voxels, with pieces alike, and their
// areas add up to the triangle's (within `relative` of it). Returns the number of pieces.
std::size_t expectSweepEqualsBoxClipping(const Corners& corners, int lo, int hi, double relative, int t,
                                         std::uint64_t* inner = nullptr) {
    const Pieces swept = sweep(corners, lo, hi, inner), clipped = clipBoxes(corners, lo, hi, 0.0);
    EXPECT_EQ(swept.size(), clipped.size()) << "triangle " << t;
    double total = 0;
    for (const auto& [voxel, piece] : clipped) {
        const auto found = swept.find(voxel);
        if (found == swept.end()) {
            ADD_FAILURE() << "triangle " << t << ": the sweep misses a voxel";
            continue;
        }
        expectSamePiece(found->second, piece, voxel);
        total += found->second.area;
    }
    EXPECT_NEAR(total, triangleArea(corners), relative * (1 + triangleArea(corners))) << "triangle " << t;
    return swept.size();
}

// Triangles in general position: exactly the voxels box clipping finds, pieces alike.
TEST(AttributeSweep, RandomTrianglesGiveTheBoxClippingPieces) {
    std::mt19937 random(12);
    std::uniform_real_distribution<double> coordinate(0.0, 8.0), size(0.01, 6.0);
    for (int t = 0; t < 300; ++t)
        expectSweepEqualsBoxClipping(randomTriangle(random, coordinate, size), -8, 16, 1e-12, t);
}

// A range that starts or ends inside the triangle (a leaf's) gets the same pieces as one
// that holds all of it.
TEST(AttributeSweep, PartialRangesGiveTheSamePieces) {
    std::mt19937 random(5);
    std::uniform_real_distribution<double> coordinate(0.0, 12.0);
    for (int t = 0; t < 100; ++t) {
        Corners corners;
        for (Point& corner : corners)
            for (std::size_t d = 0; d < 3; ++d) corner[d] = coordinate(random);
        const Pieces whole = sweep(corners, 0, 15);
        for (const auto& [lo, hi] : {std::pair{0, 5}, std::pair{6, 9}, std::pair{10, 15}}) {
            const Pieces part = sweep(corners, lo, hi);
            for (const auto& [voxel, piece] : whole) {
                const bool inside = voxel[0] >= lo && voxel[0] <= hi && voxel[1] >= lo && voxel[1] <= hi &&
                    voxel[2] >= lo && voxel[2] <= hi;
                const auto found = part.find(voxel);
                ASSERT_EQ(found != part.end(), inside) << "triangle " << t;
                if (inside) expectSamePiece(found->second, piece, voxel);
            }
        }
    }
}

// Lattice-aligned triangles (corners on voxel planes, edges through voxel corners, a
// triangle in a voxel face): the voxels with area alike; a touch (a corner or edge on a box)
// is found or lost to rounding by either way of clipping (the methods then grow the box by
// kTouchMargin), but never one the grown box does not meet. Two triangles cut their shared
// edge alike: a lattice point on it is a touch of both.
TEST(AttributeSweep, LatticeTrianglesGiveTheBoxClippingPieces) {
    const std::vector<Corners> triangles{
        {Point{0, 0, 0}, Point{12, 0, 2}, Point{0, 12, 4}},  // z = (x + 2y) / 6 through lattice points
        {Point{12, 0, 2}, Point{12, 12, 12}, Point{0, 12, 4}},
        {Point{0.5, 0.5, 3}, Point{2.5, 0.5, 3}, Point{0.5, 2.5, 3}},  // in the face z = 3
        {Point{1, 1, 1}, Point{3, 1, 1}, Point{1, 3, 3}},              // corners on voxel corners
    };
    std::vector<Pieces> swept;
    for (std::size_t t = 0; t < triangles.size(); ++t) {
        const Corners& corners = triangles[t];
        swept.push_back(sweep(corners, -1, 13));
        const Pieces exact = clipBoxes(corners, -1, 13, 0.0);
        const Pieces grown = clipBoxes(corners, -1, 13, hyvox::attributes::kTouchMargin);
        int with_area = 0;
        for (const auto& [voxel, piece] : exact) {
            if (piece.area < hyvox::attributes::kTouchArea) continue;
            ++with_area;
            const auto found = swept[t].find(voxel);
            ASSERT_NE(found, swept[t].end()) << "triangle " << t;
            expectSamePiece(found->second, piece, voxel);
        }
        int swept_with_area = 0;
        for (const auto& [voxel, piece] : swept[t]) {
            EXPECT_TRUE(grown.count(voxel)) << "triangle " << t;
            swept_with_area += piece.area >= hyvox::attributes::kTouchArea;
        }
        EXPECT_EQ(swept_with_area, with_area) << "triangle " << t;
        double total = 0;
        for (const auto& [voxel, piece] : swept[t]) total += piece.area;
        // A triangle in a voxel face is counted on both sides.
        const double expected = t == 2 ? 2 * triangleArea(corners) : triangleArea(corners);
        EXPECT_NEAR(total, expected, 1e-12) << "triangle " << t;
    }
    // (6, 6, 3) is on the edge the first two share: the voxel below that corner on the far
    // side of the edge from each meets both at that point only.
    ASSERT_TRUE(swept[0].count({6, 6, 2}) && swept[1].count({6, 6, 2}));
    EXPECT_EQ(swept[0].at({6, 6, 2}).area, 0.0);
    EXPECT_EQ(swept[1].at({6, 6, 2}).area, 0.0);
    for (std::size_t d = 0; d < 3; ++d) {
        EXPECT_EQ(swept[0].at({6, 6, 2}).centroid[d], (Point{6, 6, 3}[d]));
        EXPECT_EQ(swept[1].at({6, 6, 2}).centroid[d], (Point{6, 6, 3}[d]));
    }
}

// Large triangles, most of whose pieces come from inner columns (no edge of the triangle in
// them, measured without cutting): exactly the voxels box clipping finds, pieces alike.
TEST(AttributeSweep, LargeTrianglesGiveTheBoxClippingPiecesInInnerColumns) {
    std::mt19937 random(31);
    std::uniform_real_distribution<double> coordinate(8.0, 16.0), size(4.0, 16.0);
    std::uint64_t inner = 0, all = 0;
    for (int t = 0; t < 60; ++t)
        all += expectSweepEqualsBoxClipping(randomTriangle(random, coordinate, size), -10, 34, 1e-11, t, &inner);
    EXPECT_GT(inner, all / 4) << "the inner columns' way was hardly taken";
}

// The lattice cases of the inner columns: a large triangle in a voxel face (every inner
// piece a whole square, on both sides), planes through lattice points and lattice edges, a
// plane at 45 degrees (two dominant axes tie), a sliver. As LatticeTriangles: the pieces
// with area alike and none the grown box misses; all the area, counted twice in a face.
TEST(AttributeSweep, LatticeAlignedLargeTrianglesGiveTheBoxClippingPieces) {
    struct Case {
        Corners corners;
        bool in_face;
    };
    const std::vector<Case> cases{
        {{Point{0.5, 0.5, 3}, Point{14.5, 0.5, 3}, Point{0.5, 14.5, 3}}, true},
        {{Point{2, 0, 4}, Point{2, 14, 4}, Point{2, 0, 16}}, true},                      // in the face x = 2
        {{Point{0, 0, 0}, Point{15, 0, 5}, Point{0, 15, 10}}, false},                    // z = x / 3 + 2y / 3
        {{Point{0.5, 0.5, 0.5}, Point{14.5, 0.5, 14.5}, Point{0.5, 14.5, 0.5}}, false},  // z = x
        {{Point{0, 0, 1}, Point{16, 8, 9}, Point{0, 16, 1}}, false},  // z = x / 2 + 1, edges through lattice points
        {{Point{0.25, 0.5, 0.5}, Point{14.25, 13.5, 6.5}, Point{0.25 + 1e-4, 0.5, 0.5 + 2e-4}}, false},  // sliver
    };
    std::uint64_t inner = 0;
    for (std::size_t t = 0; t < cases.size(); ++t) {
        const Corners& corners = cases[t].corners;
        const Pieces swept = sweep(corners, -1, 17, &inner);
        const Pieces exact = clipBoxes(corners, -1, 17, 0.0);
        const Pieces grown = clipBoxes(corners, -1, 17, hyvox::attributes::kTouchMargin);
        int with_area = 0;
        for (const auto& [voxel, piece] : exact) {
            if (piece.area < hyvox::attributes::kTouchArea) continue;
            ++with_area;
            const auto found = swept.find(voxel);
            ASSERT_NE(found, swept.end()) << "case " << t;
            expectSamePiece(found->second, piece, voxel);
        }
        int swept_with_area = 0;
        double total = 0;
        for (const auto& [voxel, piece] : swept) {
            EXPECT_TRUE(grown.count(voxel)) << "case " << t;
            swept_with_area += piece.area >= hyvox::attributes::kTouchArea;
            total += piece.area;
        }
        EXPECT_EQ(swept_with_area, with_area) << "case " << t;
        const double area = triangleArea(corners);
        EXPECT_NEAR(total, cases[t].in_face ? 2 * area : area, 1e-11 * (1 + area)) << "case " << t;
    }
    EXPECT_GT(inner, 300u);
}

}  // namespace
