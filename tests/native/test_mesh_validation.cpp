// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "hyvox/errors.h"
#include "hyvox/mesh.h"

namespace {

hyvox::MeshView view(const std::vector<float>& p, const std::vector<std::uint32_t>& t) {
    return {p.data(), p.size() / 3, t.data(), t.size() / 3};
}

TEST(MeshValidation, AcceptsATriangleAndComputesBounds) {
    const std::vector<float> p{0, 0, 0, 2, 0, 0, 0, 3, -1};
    const std::vector<std::uint32_t> t{0, 1, 2};
    const auto mesh = hyvox::validate(view(p, t));
    EXPECT_EQ(mesh.usable.size(), 1u);
    EXPECT_EQ(mesh.degenerate_count, 0u);
    EXPECT_EQ(mesh.bounds.min[2], -1.0);
    EXPECT_EQ(mesh.bounds.max[0], 2.0);
    EXPECT_EQ(mesh.bounds.max[1], 3.0);
}

TEST(MeshValidation, EmptyMeshIsAClearError) {
    const std::vector<float> p;
    const std::vector<std::uint32_t> t;
    EXPECT_THROW(hyvox::validate(view(p, t)), hyvox::InvalidInput);
}

TEST(MeshValidation, NonFiniteCoordinatesAreRejected) {
    for (float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
        const std::vector<float> p{0, 0, 0, 1, 0, 0, 0, bad, 0};
        const std::vector<std::uint32_t> t{0, 1, 2};
        try {
            hyvox::validate(view(p, t));
            FAIL() << "expected InvalidInput";
        } catch (const hyvox::InvalidInput& e) {
            EXPECT_NE(std::string(e.what()).find("vertex 2"), std::string::npos) << e.what();
        }
    }
}

// Blender stores an infinite coordinate as the largest float: refused like Inf, on either
// sign; the largest coordinates below 3.4e38 are still numbers.
TEST(MeshValidation, FloatMaxCoordinatesAreRejectedAsBlendersInf) {
    const float largest = std::numeric_limits<float>::max();
    for (float bad : {largest, -largest, 3.4e38f, -3.4e38f}) {
        const std::vector<float> p{0, 0, 0, 1, 0, 0, 0, 0, bad};
        const std::vector<std::uint32_t> t{0, 1, 2};
        try {
            hyvox::validate(view(p, t));
            FAIL() << "expected InvalidInput for " << bad;
        } catch (const hyvox::InvalidInput& e) {
            EXPECT_NE(std::string(e.what()).find("vertex 2 has a non-finite coordinate"), std::string::npos)
                << e.what();
            EXPECT_NE(std::string(e.what()).find("Inf as Blender stores it"), std::string::npos) << e.what();
        }
    }
    const float below = std::nextafter(3.4e38f, 0.0f);
    const std::vector<float> p{0, 0, 0, 1, 0, 0, 0, 0, below};
    const std::vector<std::uint32_t> t{0, 1, 2};
    EXPECT_NO_THROW(hyvox::validate(view(p, t)));
}

// Two bad vertices in one chunk of the parallel check: the message names the first.
TEST(MeshValidation, TheFirstBadVertexOfAChunkIsNamed) {
    std::vector<float> p(3 * 12, 0.0f);
    for (int v = 0; v < 12; ++v) p[3 * v] = float(v);
    p[3 * 1 + 1] = 1.0f;
    p[3 * 5 + 2] = std::numeric_limits<float>::quiet_NaN();
    p[3 * 9] = std::numeric_limits<float>::infinity();
    const std::vector<std::uint32_t> t{0, 1, 2};
    try {
        hyvox::validate(view(p, t));
        FAIL() << "expected InvalidInput";
    } catch (const hyvox::InvalidInput& e) {
        EXPECT_NE(std::string(e.what()).find("vertex 5 has a non-finite coordinate"), std::string::npos) << e.what();
        EXPECT_EQ(std::string(e.what()).find("vertex 9"), std::string::npos) << e.what();
    }
}

TEST(MeshValidation, OutOfRangeIndexIsRejected) {
    const std::vector<float> p{0, 0, 0, 1, 0, 0, 0, 1, 0};
    const std::vector<std::uint32_t> t{0, 1, 3};
    EXPECT_THROW(hyvox::validate(view(p, t)), hyvox::InvalidInput);
}

TEST(MeshValidation, DegenerateTrianglesAreSkippedAndCounted) {
    // Repeated index, collinear vertices, and one good triangle.
    const std::vector<float> p{0, 0, 0, 1, 0, 0, 2, 0, 0, 0, 1, 0};
    const std::vector<std::uint32_t> t{0, 0, 1, 0, 1, 2, 0, 1, 3};
    const auto mesh = hyvox::validate(view(p, t));
    EXPECT_EQ(mesh.degenerate_count, 2u);
    ASSERT_EQ(mesh.usable.size(), 1u);
    EXPECT_EQ(mesh.usable[0], 2u);
    // Bounds come from usable triangles only: vertex 2 (x=2) is used by degenerates alone.
    EXPECT_EQ(mesh.bounds.max[0], 1.0);
}

TEST(MeshValidation, AllDegenerateIsAClearError) {
    const std::vector<float> p{0, 0, 0, 1, 1, 1, 2, 2, 2};
    const std::vector<std::uint32_t> t{0, 1, 2};
    EXPECT_THROW(hyvox::validate(view(p, t)), hyvox::InvalidInput);
}

// validate() checks chunks of 65,536 vertices / triangles in parallel. A mesh of several
// chunks with degenerate triangles scattered over them (runs of them, whole degenerate
// chunks) against a plain serial pass written here: the same usable list, count and bounds.
struct ScatteredMesh {
    std::vector<float> positions;
    std::vector<std::uint32_t> triangles;
};

ScatteredMesh scatteredMesh(std::size_t triangles, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> coord(-50.0f, 50.0f);
    ScatteredMesh m;
    const std::size_t vertices = triangles / 2 + 3;
    for (std::size_t i = 0; i < 3 * vertices; ++i) m.positions.push_back(coord(rng));
    std::uniform_int_distribution<std::uint32_t> vertex(0, std::uint32_t(vertices - 1));
    for (std::size_t t = 0; t < triangles; ++t) {
        const std::uint32_t a = vertex(rng), b = vertex(rng), c = vertex(rng);
        // Degenerate: all of chunk 1 (65,536..131,071), every 7th triangle, a run in chunk 3.
        const bool degenerate = (t >= 65536 && t < 131072) || t % 7 == 3 || (t >= 200000 && t < 200100);
        if (degenerate)
            m.triangles.insert(m.triangles.end(), {a, a, c});
        else
            m.triangles.insert(m.triangles.end(), {a, b, c});
    }
    return m;
}

TEST(MeshValidation, ChunkedPassEqualsASerialPass) {
    const ScatteredMesh m = scatteredMesh(300000, 5);
    const auto mesh = hyvox::validate(view(m.positions, m.triangles));
    std::vector<std::uint32_t> usable;
    double lo[3] = {1e30, 1e30, 1e30}, hi[3] = {-1e30, -1e30, -1e30};
    for (std::size_t t = 0; t < m.triangles.size() / 3; ++t) {
        const std::uint32_t* idx = &m.triangles[3 * t];
        const float* a = &m.positions[3 * idx[0]];
        const float* b = &m.positions[3 * idx[1]];
        const float* c = &m.positions[3 * idx[2]];
        const double e0[3] = {double(b[0]) - a[0], double(b[1]) - a[1], double(b[2]) - a[2]};
        const double e1[3] = {double(c[0]) - a[0], double(c[1]) - a[1], double(c[2]) - a[2]};
        const bool zero = e0[1] * e1[2] - e0[2] * e1[1] == 0 && e0[2] * e1[0] - e0[0] * e1[2] == 0 &&
            e0[0] * e1[1] - e0[1] * e1[0] == 0;
        if (idx[0] == idx[1] || idx[1] == idx[2] || idx[0] == idx[2] || zero) continue;
        usable.push_back(std::uint32_t(t));
        for (const float* p : {a, b, c})
            for (int axis = 0; axis < 3; ++axis) {
                lo[axis] = std::min(lo[axis], double(p[axis]));
                hi[axis] = std::max(hi[axis], double(p[axis]));
            }
    }
    EXPECT_EQ(mesh.usable, usable);
    EXPECT_EQ(mesh.degenerate_count, m.triangles.size() / 3 - usable.size());
    for (int axis = 0; axis < 3; ++axis) {
        EXPECT_EQ(mesh.bounds.min[axis], lo[axis]);
        EXPECT_EQ(mesh.bounds.max[axis], hi[axis]);
    }
}

// The sums the memory estimate takes from validate() (TriangleSums), against a serial pass in
// long double over the triangles the serial pass above keeps: a mesh of several chunks, moved
// far from the world's origin (the volume's apex must follow the mesh, not the origin).
TEST(MeshValidation, TheTriangleSumsEqualASerialSum) {
    ScatteredMesh m = scatteredMesh(300000, 9);
    for (std::size_t i = 0; i < m.positions.size(); ++i) m.positions[i] += i % 3 == 0 ? 20000.0f : -7000.0f;
    const auto mesh = hyvox::validate(view(m.positions, m.triangles));
    long double crossed = 0, volume = 0, normal[3] = {0, 0, 0};
    for (const std::uint32_t t : mesh.usable) {
        const std::uint32_t* idx = &m.triangles[3 * std::size_t(t)];
        long double p[3][3];
        for (int c = 0; c < 3; ++c)
            for (int axis = 0; axis < 3; ++axis)
                p[c][axis] = (long double)m.positions[3 * std::size_t(idx[c]) + axis] - mesh.bounds.min[axis];
        const long double e0[3] = {p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]};
        const long double e1[3] = {p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
        const long double n[3] = {e0[1] * e1[2] - e0[2] * e1[1], e0[2] * e1[0] - e0[0] * e1[2],
                                  e0[0] * e1[1] - e0[1] * e1[0]};
        crossed += (std::fabs(n[0]) + std::fabs(n[1]) + std::fabs(n[2])) / 2;
        volume += (p[0][0] * n[0] + p[0][1] * n[1] + p[0][2] * n[2]) / 6;
        for (int axis = 0; axis < 3; ++axis) normal[axis] += n[axis] / 6;
    }
    EXPECT_NEAR(mesh.sums.crossed_area, double(crossed), 1e-12 * double(crossed));
    // The volume of a soup of random triangles is a sum of terms of both signs: compared with
    // the size of those terms.
    const double scale = double(crossed) * 100.0;
    EXPECT_NEAR(mesh.sums.volume, double(volume), 1e-12 * scale);
    for (int axis = 0; axis < 3; ++axis)
        EXPECT_NEAR(mesh.sums.normal[axis], double(normal[axis]), 1e-12 * double(crossed));
}

// A closed cube of side 2 far from the origin, faces outward, and a triangle with a repeated
// corner (skipped): the volume is the cube's (8), the normals cancel, the crossed area is the
// cube's area (its faces are axis-aligned: |n|₁ is twice a face triangle's area).
TEST(MeshValidation, TheTriangleSumsOfACubeAreItsVolumeAndArea) {
    std::vector<float> p;
    for (int v = 0; v < 8; ++v)
        p.insert(
            p.end(),
            {1000.0f + 2.0f * float(v & 1), -500.0f + 2.0f * float((v >> 1) & 1), 3.0f + 2.0f * float((v >> 2) & 1)});
    const std::vector<std::uint32_t> t{0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4, 2, 6,
                                       3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5, 1, 1, 3};
    const auto mesh = hyvox::validate(view(p, t));
    EXPECT_EQ(mesh.degenerate_count, 1u);
    EXPECT_DOUBLE_EQ(mesh.sums.volume, 8.0);
    EXPECT_DOUBLE_EQ(mesh.sums.crossed_area, 24.0);
    for (int axis = 0; axis < 3; ++axis) EXPECT_EQ(mesh.sums.normal[axis], 0.0);
}

// Problems in several chunks: the message names the first, as a serial pass would.
TEST(MeshValidation, TheFirstProblemIsReportedWhateverTheChunk) {
    ScatteredMesh m = scatteredMesh(300000, 9);
    const auto vertices = std::uint32_t(m.positions.size() / 3);
    m.triangles[3 * 250000 + 1] = vertices + 5;
    m.triangles[3 * 140000 + 2] = vertices;
    m.triangles[3 * 140001] = vertices + 1;
    try {
        hyvox::validate(view(m.positions, m.triangles));
        FAIL() << "expected InvalidInput";
    } catch (const hyvox::InvalidInput& e) {
        EXPECT_NE(std::string(e.what()).find("triangle 140000 refers to vertex " + std::to_string(vertices)),
                  std::string::npos)
            << e.what();
    }
    m.positions[3 * 140000 + 1] = std::numeric_limits<float>::quiet_NaN();
    m.positions[3 * 70000] = std::numeric_limits<float>::infinity();
    try {
        hyvox::validate(view(m.positions, m.triangles));
        FAIL() << "expected InvalidInput";
    } catch (const hyvox::InvalidInput& e) {
        EXPECT_NE(std::string(e.what()).find("vertex 70000 has a non-finite"), std::string::npos) << e.what();
    }
}

}  // namespace
