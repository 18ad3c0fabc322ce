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
#include "attributes/sweep_cells.h"

namespace {

using hyvox::attributes::ClippedPiece;
using hyvox::attributes::Point;
using hyvox::attributes::SweepLines;
using hyvox::attributes::TracedPolygon;
using hyvox::attributes::TriangleFrame;
using Corners = std::array<Point, 3>;
using Voxel = std::array<int, 3>;
using Pieces = std::map<Voxel, ClippedPiece>;

// Every piece of the triangle in the voxels of [lo, hi]³, by the sweep.
Pieces sweep(const Corners& corners, int lo, int hi) {
    const TriangleFrame frame(corners);
    SweepLines lines;
    const TracedPolygon whole = tracedTriangle(corners, lines);
    Pieces pieces;
    using hyvox::attributes::sweepSlabs;
    sweepSlabs<0>(whole, lo, hi, lines, true, [&](int i, const TracedPolygon& slab) {
        sweepSlabs<1>(slab, lo, hi, lines, true, [&](int j, const TracedPolygon& column) {
            sweepSlabs<2>(column, lo, hi, lines, false, [&](int k, const TracedPolygon& cell) {
                ClippedPiece piece;
                measurePiece(cell.shape, frame, piece);
                EXPECT_TRUE(pieces.emplace(Voxel{i, j, k}, piece).second) << "voxel visited twice";
            });
        });
    });
    return pieces;
}

// The same by clipping the triangle to every box of [lo, hi]³ (grown by `margin`).
Pieces clipBoxes(const Corners& corners, int lo, int hi, double margin) {
    const TriangleFrame frame(corners);
    Pieces pieces;
    for (int i = lo; i <= hi; ++i)
        for (int j = lo; j <= hi; ++j)
            for (int k = lo; k <= hi; ++k) {
                ClippedPiece piece;
                if (clipTriangleToVoxel(corners, {i, j, k}, frame, piece, margin)) pieces.emplace(Voxel{i, j, k}, piece);
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
    for (std::size_t d = 0; d < 3; ++d) EXPECT_NEAR(got.centroid[d], expected.centroid[d], 1e-9) << v[0] << " " << v[1] << " " << v[2];
}

// Triangles in general position: exactly the voxels box clipping finds, pieces alike.
TEST(AttributeSweep, RandomTrianglesGiveTheBoxClippingPieces) {
    std::mt19937 random(12);
    std::uniform_real_distribution<double> coordinate(0.0, 8.0), size(0.01, 6.0);
    for (int t = 0; t < 300; ++t) {
        const Point centre{coordinate(random), coordinate(random), coordinate(random)};
        const double scale = size(random);
        std::uniform_real_distribution<double> offset(-scale, scale);
        Corners corners;
        for (Point& corner : corners)
            for (std::size_t d = 0; d < 3; ++d) corner[d] = centre[d] + offset(random);
        const Pieces swept = sweep(corners, -8, 16), clipped = clipBoxes(corners, -8, 16, 0.0);
        ASSERT_EQ(swept.size(), clipped.size()) << "triangle " << t;
        double total = 0;
        for (const auto& [voxel, piece] : clipped) {
            const auto found = swept.find(voxel);
            ASSERT_NE(found, swept.end()) << "triangle " << t;
            expectSamePiece(found->second, piece, voxel);
            total += found->second.area;
        }
        EXPECT_NEAR(total, triangleArea(corners), 1e-12 * (1 + triangleArea(corners))) << "triangle " << t;
    }
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

}  // namespace
