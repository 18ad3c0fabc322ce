// SPDX-License-Identifier: GPL-3.0-or-later
// The tessellation method's CPU pieces, no GL needed: Eq. 1 factors and the pre-split, the
// vertex normals, the displacement image (PNG), the tests' CPU twins of the surface (PN,
// sampling) and subdivision, and the accuracy measures (bias, false voxels, ray-marching
// and flood watertightness, the Eq. 3 fit).
#include <gtest/gtest.h>
#include <png.h>
#include <zlib.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "hyvox/accuracy.h"
#include "hyvox/errors.h"
#include "hyvox/texture.h"
#include "hyvox/voxelize.h"
#include "support/subdivide.h"
#include "support/surface_twin.h"
#include "support/triangle_soup.h"
#include "tessellation/displacement_map.h"
#include "tessellation/surface_attributes.h"
#include "tessellation/tess_factors.h"

namespace hyvox {
namespace {

using namespace tessellation;
using test::SurfacePoint;
using test::SurfaceTwin;
using test::Vec3d;

// `grid` with voxel (i,j,k) cleared.
BitGrid without(BitGrid grid, int i, int j, int k) {
    grid.data()[grid.wordIndex(i, j, k)] &= ~BitGrid::bitMask(j, k);
    return grid;
}

TEST(TessellationFactors, EquationOneUsesTheEdgeLength) {
    // Edge (0,0,0)-(3,-5,1): length sqrt(9 + 25 + 1) voxels, times γ.
    EXPECT_DOUBLE_EQ(edgeFactor({0, 0, 0}, {3, -5, 1}, 1.0), std::sqrt(35.0));
    EXPECT_DOUBLE_EQ(edgeFactor({0, 0, 0}, {3, -5, 1}, 2.0), 2.0 * std::sqrt(35.0));
    const PatchFactors f = patchFactors({0, 0, 0}, {4, 0, 0}, {0, 2, 0}, 1.0);
    EXPECT_DOUBLE_EQ(f.outer[0], std::sqrt(20.0));  // corners 1-2
    EXPECT_DOUBLE_EQ(f.outer[1], 2.0);              // corners 2-0
    EXPECT_DOUBLE_EQ(f.outer[2], 4.0);              // corners 0-1
    EXPECT_DOUBLE_EQ(f.inner, (std::sqrt(20.0) + 6.0) / 3.0);
}

TEST(TessellationFactors, PreSplitKeepsEveryFactorUnderTheLimit) {
    // Longest edges 64 and 65 voxels (the others about 45).
    EXPECT_EQ(presplitPieces(patchFactors({0, 0, 0}, {64, 0, 0}, {32, 32, 0}, 1.0), 64), 1);
    EXPECT_EQ(presplitPieces(patchFactors({0, 0, 0}, {65, 0, 0}, {32, 32, 0}, 1.0), 64), 2);
    // A tetrahedron face at 1024³ with γ = 4: its hypotenuse 1024·√2 gives 4·1448.2 / 64 = 90.5,
    // so 91 pieces per edge.
    const PatchFactors big = patchFactors({0, 0, 0}, {1024, 0, 0}, {0, 1024, 0}, 4.0);
    const int n = presplitPieces(big, 64);
    EXPECT_EQ(n, 91);
    EXPECT_LE(big.largest() / n, 64.0);
}

// An octahedron on the unit sphere (outward normals = positions), in a grid of voxel size 1.
struct Octahedron {
    std::vector<float> positions{1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1};
    std::vector<std::uint32_t> triangles{0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
    std::vector<float> uvs = std::vector<float>(12, 0.5f);
    MeshView view() const {
        MeshView v{positions.data(), 6, triangles.data(), 8};
        v.uvs = uvs.data();
        return v;
    }
};
GridSpec unitGrid() {
    GridSpec g;
    g.origin = {0, 0, 0};
    g.voxel_size = 1.0;
    g.dims = {4, 4, 4};
    return g;
}

TEST(TessellationSurface, PnTrianglesInterpolateCornersAndBulgeTowardsTheSphere) {
    const Octahedron octa;
    const ValidatedMesh mesh = validate(octa.view());
    const SurfaceTwin surface(mesh, unitGrid());
    for (std::uint32_t t = 0; t < 8; ++t) {
        const auto corners = surface.corners(t);
        for (int c = 0; c < 3; ++c) {
            Vec3d w{0, 0, 0};
            w[c] = 1;
            const SurfacePoint p = surface.evaluate(t, w, true);
            for (int a = 0; a < 3; ++a) EXPECT_NEAR(p.position[a], corners[c][a], 1e-6);
        }
        // The face centre: flat lies at radius 1/√3, PN much closer to the unit sphere.
        const Vec3d centre{1.0 / 3, 1.0 / 3, 1.0 / 3};
        auto radius = [](const SurfacePoint& p) {
            return std::sqrt(p.position[0] * p.position[0] + p.position[1] * p.position[1] +
                             p.position[2] * p.position[2]);
        };
        const double flat = radius(surface.evaluate(t, centre, false));
        const double pn = radius(surface.evaluate(t, centre, true));
        EXPECT_NEAR(flat, 1.0 / std::sqrt(3.0), 1e-6);
        EXPECT_LT(std::abs(pn - 1.0), std::abs(flat - 1.0));  // a cubic overshoots an octahedron, still closer
    }
}

TEST(TessellationSurface, AreaWeightedNormalsPointOutwards) {
    const Octahedron octa;
    const SurfaceAttributes attributes(validate(octa.view()), unitGrid());
    for (std::size_t v = 0; v < 6; ++v)
        for (int a = 0; a < 3; ++a) EXPECT_NEAR(attributes.normals()[3 * v + a], octa.positions[3 * v + a], 1e-6);
}

TEST(DisplacementMap, SamplesLikeGlLinearClampToEdge) {
    // 2×2, row 0 = top: top row 0, 1; bottom row 2, 3.
    const DisplacementMap map(HeightImage{2, 2, {0, 1, 2, 3}});
    EXPECT_FLOAT_EQ(test::sampleHeight(map, 0.25, 0.25), 2.0f);  // bottom-left texel centre
    EXPECT_FLOAT_EQ(test::sampleHeight(map, 0.75, 0.75), 1.0f);  // top-right
    EXPECT_FLOAT_EQ(test::sampleHeight(map, 0.5, 0.5), 1.5f);    // the mean of all four
    EXPECT_FLOAT_EQ(test::sampleHeight(map, 0.0, 0.0), 2.0f);    // clamped at the edge
    EXPECT_FLOAT_EQ(test::sampleHeight(map, -5.0, 9.0), 0.0f);   // far outside: the top-left texel
    EXPECT_THROW(DisplacementMap(HeightImage{2, 2, {0, 1, 2}}), InvalidInput);
}

void writePng(const std::string& path, int width, int height, int depth, const std::vector<std::uint16_t>& grey) {
    png_image image{};
    image.version = PNG_IMAGE_VERSION;
    image.width = png_uint_32(width);
    image.height = png_uint_32(height);
    image.format = depth == 16 ? PNG_FORMAT_LINEAR_Y : PNG_FORMAT_GRAY;
    bool ok;
    if (depth == 16) {
        ok = png_image_write_to_file(&image, path.c_str(), 0, grey.data(), 0, nullptr);
    } else {
        std::vector<png_byte> bytes(grey.begin(), grey.end());
        ok = png_image_write_to_file(&image, path.c_str(), 0, bytes.data(), 0, nullptr);
    }
    ASSERT_TRUE(ok) << image.message;
}

TEST(DisplacementMap, ReadsEightAndSixteenBitGreyPng) {
    const auto dir = std::filesystem::temp_directory_path();
    const std::string p8 = (dir / "hyvox_test_height8.png").string();
    const std::string p16 = (dir / "hyvox_test_height16.png").string();
    writePng(p8, 3, 2, 8, {0, 51, 255, 102, 153, 204});
    writePng(p16, 2, 1, 16, {0, 65535});
    const HeightImage h8 = hyvox::readPngHeight(p8);
    ASSERT_EQ(h8.width, 3);
    ASSERT_EQ(h8.height, 2);
    EXPECT_NEAR(h8.values[1], 0.2f, 1e-6);
    EXPECT_NEAR(h8.values[2], 1.0f, 1e-6);
    EXPECT_NEAR(h8.values[3], 0.4f, 1e-6);
    const HeightImage h16 = hyvox::readPngHeight(p16);
    EXPECT_NEAR(h16.values[0], 0.0f, 1e-6);
    EXPECT_NEAR(h16.values[1], 1.0f, 1e-6);
    std::filesystem::remove(p8);
    std::filesystem::remove(p16);
    EXPECT_THROW(hyvox::readPngHeight((dir / "hyvox_no_such_file.png").string()), InvalidInput);
}

// A PNG whose header says 9000 x 9000 (81 M texels) and holds no pixels: the texel limit of
// every image hyvox reads refuses it before anything is allocated for its pixels.
TEST(DisplacementMap, AHeightImagePastTheTexelLimitIsRefusedBeforeDecoding) {
    auto chunk = [](const char* type, const std::string& data) {
        auto be32 = [](std::uint32_t v) { return std::string{char(v >> 24), char(v >> 16), char(v >> 8), char(v)}; };
        const std::string body = std::string(type, 4) + data;
        return be32(std::uint32_t(data.size())) + body +
            be32(std::uint32_t(crc32(0, reinterpret_cast<const Bytef*>(body.data()), uInt(body.size()))));
    };
    const std::string size = std::string("\0\0\x23\x28", 4);  // 9000
    const std::string png = std::string("\x89PNG\r\n\x1a\n", 8) +
        chunk("IHDR", size + size + std::string("\x08\0\0\0\0", 5)) + chunk("IDAT", "x") + chunk("IEND", "");
    const std::string path = (std::filesystem::temp_directory_path() / "hyvox_test_huge_height.png").string();
    std::FILE* file = std::fopen(path.c_str(), "wb");
    ASSERT_NE(file, nullptr);
    std::fwrite(png.data(), 1, png.size(), file);
    std::fclose(file);
    try {
        hyvox::readPngHeight(path);
        ADD_FAILURE() << "read";
    } catch (const InvalidInput& e) {
        EXPECT_NE(std::string(e.what()).find("has 9000x9000 texels, more than the limit of 8192x8192"),
                  std::string::npos)
            << e.what();
    }
    std::filesystem::remove(path);
}

TEST(CpuSubdivide, MidpointSubdivisionQuadruplesAndSharesEdges) {
    const Octahedron octa;
    const Mesh once = test::midpointSubdivide(octa.view(), 1);
    EXPECT_EQ(once.triangleCount(), 32u);
    EXPECT_EQ(once.vertexCount(), 6u + 12u);  // one new vertex per edge
    const Mesh twice = test::midpointSubdivide(octa.view(), 2);
    EXPECT_EQ(twice.triangleCount(), 128u);
    EXPECT_EQ(twice.uvs.size(), 2 * twice.vertexCount());
}

TEST(CpuSubdivide, SubdivideAndDisplaceMovesVerticesAlongTheNormal) {
    const Octahedron octa;
    const ValidatedMesh mesh = validate(octa.view());
    TessellationOptions options;
    options.displacement_pixels = HeightImage{1, 1, {1.0f}};
    options.displacement_strength = 0.25;
    options.displacement_midlevel = 0.5;
    const Mesh out = test::subdivideAndDisplace(mesh, unitGrid(), options, 3);
    EXPECT_EQ(out.triangleCount(), 8u * 9u);
    // Corner vertices sit on the unit sphere with radial normals: displaced to r = 1.125.
    const float* p = out.positions.data();
    EXPECT_NEAR(std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]), 1.125, 1e-6);
}

BitGrid gridWith(std::initializer_list<std::array<int, 3>> voxels, std::array<std::int32_t, 3> dims = {8, 8, 8}) {
    BitGrid g(dims);
    for (const auto& v : voxels) g.set(v[0], v[1], v[2]);
    return g;
}

TEST(Accuracy, BiasAndFalseVoxels) {
    const BitGrid reference = gridWith({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}});
    const BitGrid result = gridWith({{0, 0, 0}, {1, 0, 0}, {5, 5, 5}});
    const AccuracyReport r = compareToReference(result, reference);
    EXPECT_EQ(r.reference_voxels, 4u);
    EXPECT_EQ(r.missed_voxels, 2u);
    EXPECT_EQ(r.false_voxels, 1u);
    EXPECT_DOUBLE_EQ(r.bias, 0.5);
    const auto extra = falseVoxels(result, reference);
    ASSERT_EQ(extra.size(), 1u);
    EXPECT_EQ(extra[0], (std::array<std::int32_t, 3>{5, 5, 5}));
}

TEST(Accuracy, WatertightnessCatchesAHoleThatABackWallWouldHide) {
    // A box with faces at voxel centres (1.5 .. 6.5 in an 8³ grid of unit voxels): each face
    // is one voxel thick in its exact conservative voxelization.
    test::TriangleSoup box;
    box.addBox({1.5, 1.5, 1.5}, {6.5, 6.5, 6.5});
    const ValidatedMesh mesh = validate(box.view());
    VoxelizeOptions o;
    o.method = Method::Cpu;
    o.grid.voxel_size = 1.0;
    o.grid.origin = std::array<double, 3>{0, 0, 0};
    o.grid.bounds = Bounds{{0, 0, 0}, {8, 8, 8}};
    const VoxelizeResult exact = voxelize(box.view(), o);
    const WatertightReport whole = rayMarchWatertightness(exact.occupancy, exact.occupancy, mesh, exact.grid);
    EXPECT_EQ(whole.rays, 6u * 64u);
    EXPECT_EQ(whole.passed, whole.rays);
    const BitGrid holed = without(exact.occupancy.toBitGrid(), 3, 3, 1);  // a hole in the z = 1.5 face
    const WatertightReport r = rayMarchWatertightness(holed, exact.occupancy.toBitGrid(), mesh, exact.grid);
    // Only the +z ray through column (3,3) slips through (to the far face at k = 6); the rays
    // along x and y meet the hole's voxel inside the run of their first face, not first.
    EXPECT_EQ(r.rays - r.passed, 1u);
}

TEST(Accuracy, FloodFindsTheEnclosedVoxelsAndAPinholeIntoThem) {
    // A hollow 4³ shell of voxels (3..6 on every axis) in a 10³ grid encloses 2³ voxels; a
    // copy with one shell voxel removed lets the flood from outside in, a copy with a corner
    // voxel removed does not (a corner gap is no 6-connected path), and a lone voxel
    // encloses nothing.
    BitGrid shell({10, 10, 10});
    for (int i = 3; i <= 6; ++i)
        for (int j = 3; j <= 6; ++j)
            for (int k = 3; k <= 6; ++k)
                if (i == 3 || i == 6 || j == 3 || j == 6 || k == 3 || k == 6) shell.set(i, j, k);
    const SealReport same = floodFromOutside(shell, shell);
    EXPECT_EQ(same.enclosed, 8u);
    EXPECT_EQ(same.leaked, 0u);
    EXPECT_TRUE(same.sealed());

    const BitGrid pinhole = without(shell, 4, 5, 3);
    const SealReport leak = floodFromOutside(pinhole, shell);
    EXPECT_EQ(leak.enclosed, 8u);
    EXPECT_EQ(leak.leaked, 8u);
    EXPECT_FALSE(leak.sealed());

    const BitGrid corner = without(shell, 3, 3, 3);
    EXPECT_TRUE(floodFromOutside(corner, shell).sealed());

    EXPECT_EQ(floodFromOutside(shell, gridWith({{0, 0, 0}}, {10, 10, 10})).enclosed, 0u);
    EXPECT_THROW(floodFromOutside(shell, BitGrid({10, 10, 9})), InvalidInput);
}

TEST(Accuracy, GammaFitRecoversEquationThree) {
    const double A = 40.0, B = 1.5;
    std::vector<double> gammas{1, 2, 3, 4}, biases;
    for (double g : gammas) biases.push_back(std::exp(-g / B) / A);
    const GammaBiasFit fit = fitGammaBias(gammas, biases);
    EXPECT_NEAR(fit.A, A, 1e-9 * A);
    EXPECT_NEAR(fit.B, B, 1e-12);
    EXPECT_NEAR(fit.gammaFor(biases[2]), 3.0, 1e-9);
    EXPECT_NEAR(fit.biasFor(2.0), biases[1], 1e-15);
    EXPECT_THROW(fitGammaBias({1, 2}, {0.1, 0.1}), InvalidInput);
}

}  // namespace
}  // namespace hyvox
