// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
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

}  // namespace
