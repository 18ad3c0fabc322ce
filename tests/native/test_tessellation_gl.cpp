// SPDX-License-Identifier: GPL-3.0-or-later
// The tessellation method on the GL device (llvmpipe in CI, never skipped): accuracy against
// the exact cpu voxelization on real meshes, gap-freeness of huge triangles (pre-split),
// PN-triangles, displacement, and point counts.
#include <gtest/gtest.h>

#include <png.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <cstdio>
#include <map>
#include <ostream>
#include <set>
#include <stdexcept>

#include "hyvox/accuracy.h"
#include "hyvox/errors.h"
#include "hyvox/voxelize.h"
#include "support/subdivide.h"
#include "support/surface_twin.h"
#include "support/temp_dir.h"
#include "support/test_mesh_loader.h"
#include "support/triangle_soup.h"
#include "support/voxel_checks.h"
#include "tessellation/displacement_map.h"

namespace hyvox {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kTouchEps = 1e-5;  // voxel units, the hybrid issue's touch rule

VoxelizeOptions optionsFor(Method method, int resolution, double gamma = 1.0, Mode mode = Mode::Conservative) {
    VoxelizeOptions o;
    o.method = method;
    o.mode = mode;
    o.grid.resolution = resolution;
    o.tessellation.gamma = gamma;
    return o;
}

// The tessellation section of the method's stats.
const TessellationStats& tess(const VoxelizeResult& r) {
    if (!r.stats.tessellation) throw std::runtime_error("no tessellation stats in the result");
    return *r.stats.tessellation;
}

std::uint64_t countSum(const VoxelizeResult& r) {
    std::uint64_t sum = 0;
    for (const auto& c : r.counts) sum += c.count;
    return sum;
}

// Voxels only `result` has, beyond the exact conservative set, that are not touches within
// eps (the shared oracle check, double precision): these would be real false voxels. The
// conservative voxels it lacks are the method's bias, measured apart.
std::uint64_t falseBeyondTouch(const MeshView& mesh, const VoxelizeResult& result, const VoxelizeResult& conservative,
                               double eps) {
    return test::compareResults(mesh, Mode::Conservative, result, conservative, eps).unexplained_result_only;
}

VoxelizeResult conservativeVoxels(const MeshView& mesh, VoxelizeOptions o) {
    o.method = Method::Cpu;
    o.mode = Mode::Conservative;
    return voxelize(mesh, o);
}

WatertightReport watertightness(const MeshView& mesh, const VoxelizeResult& r, const VoxelizeResult& conservative) {
    return rayMarchWatertightness(r.occupancy, conservative.occupancy, validate(mesh), r.grid);
}

// --- real meshes: bias, false voxels, watertightness, counts -------------------------------

struct MeshCase {
    const char* file;
    bool closed;
};
void PrintTo(const MeshCase& m, std::ostream* os) { *os << m.file; }
class TessellationMeshes : public ::testing::TestWithParam<std::tuple<MeshCase, int>> {};

// Measured on llvmpipe (bias against the exact conservative voxels): γ=1 0.118-0.172,
// γ=2 0.066-0.093, γ=4 0.035-0.049 over these six cases. The issue asked for ≤ 5% at γ=1;
// one point per micro-triangle of edge ≤ 1/γ voxel cannot reach that against an oracle that
// keeps every voxel the surface merely clips, so the bounds below are γ=1 ≤ 20% and γ=4 ≤ 5%,
// with the bias strictly falling as γ grows (against the thin, 6-separating set the same γ=1
// points miss only 0.3-0.6%: they lie between the two). Watertightness (the strict ray test)
// at γ=1 leaves a few pinholes where the tessellator's rings space points just over a voxel
// apart (e.g. 5 rays of 786k on the Buddha at 256, enough for a flood from outside to fill
// its inside); from γ=2 on no ray fails and no flood gets in. Other readings of Eq. 1
// (fractional-odd partitioning, Euclidean edge length) do not change this picture:
// bench/README.md, "Other readings of Eq. 1".
TEST_P(TessellationMeshes, BiasFallsWithGammaAndNothingFalseOrLeaking) {
    const auto [mesh_case, resolution] = GetParam();
    const test::TestMesh mesh = test::loadTestMesh(test::meshPath(mesh_case.file));
    // One empty layer all around, so the flood below reaches the whole outside.
    auto padded = [&](Method method, double gamma) {
        VoxelizeOptions o = optionsFor(method, resolution, gamma);
        o.grid.padding = 1;
        return o;
    };
    const VoxelizeResult conservative = conservativeVoxels(mesh.view(), padded(Method::Cpu, 1.0));
    const std::vector<char> inside = mesh_case.closed ? test::insideByParity(mesh.view(), conservative.grid)
                                                      : std::vector<char>();
    double previous_bias = 1.0;
    for (double gamma : {1.0, 2.0, 4.0}) {
        const VoxelizeResult r = voxelize(mesh.view(), padded(Method::Tessellation, gamma));
        const AccuracyReport acc = compareToReference(r.occupancy, conservative.occupancy);
        const WatertightReport rays = watertightness(mesh.view(), r, conservative);
        std::printf("%s @%d γ=%g: %llu points, %llu voxels, bias %.4f, false %llu, watertight %.6f (%llu rays fail), "
                    "%.0f ms\n",
                    mesh_case.file, resolution, gamma, (unsigned long long)tess(r).points,
                    (unsigned long long)r.stats.voxel_count, acc.bias, (unsigned long long)acc.false_voxels,
                    rays.share(), (unsigned long long)(rays.rays - rays.passed), tess(r).pass1_gpu_ms);
        EXPECT_EQ(falseBeyondTouch(mesh.view(), r, conservative, kTouchEps), 0u)
            << acc.false_voxels << " false voxels, not all touches";
        EXPECT_LE(acc.bias, gamma == 1.0 ? 0.20 : (gamma == 2.0 ? 0.12 : 0.05)) << "γ=" << gamma;
        EXPECT_LT(acc.bias, previous_bias) << "γ=" << gamma;
        previous_bias = acc.bias;
        if (mesh_case.closed) {
            // Independent of the ray test: the empty voxels 6-connected to the outside must
            // not reach a voxel whose centre is inside the mesh (parity of a ray, in double).
            const test::Separation flood = test::floodFromBoundary(r.occupancy.toBitGrid(), inside);
            std::printf("  flood: %llu empty inside, %llu of them reached from outside\n",
                        (unsigned long long)flood.inside_empty, (unsigned long long)flood.inside_reached);
            EXPECT_GT(flood.inside_empty, 0u);
            if (gamma == 1.0) {
                EXPECT_GE(rays.share(), 0.9999);
            } else {
                EXPECT_EQ(rays.passed, rays.rays) << "γ=" << gamma;
                EXPECT_EQ(flood.inside_reached, 0u) << "γ=" << gamma;
            }
        }
        EXPECT_EQ(countSum(r), tess(r).points);
        EXPECT_EQ(tess(r).points_clipped, 0u);
        EXPECT_EQ(r.counts.size(), r.stats.voxel_count);
    }
}

INSTANTIATE_TEST_SUITE_P(
    Meshes, TessellationMeshes,
    ::testing::Combine(::testing::Values(MeshCase{"bunny_stanford_69k.ply", false},
                                         MeshCase{"happy_buddha_100k.ply", true},
                                         MeshCase{"dragon_stanford_res2_203k.ply.gz", true}),
                       ::testing::Values(128, 256)),
    [](const auto& test_info) {
        std::string name = std::get<0>(test_info.param).file;
        name = name.substr(0, name.find('_'));
        return name + "_" + std::to_string(std::get<1>(test_info.param));
    });

// --- huge triangles: the pre-split keeps them gap-free --------------------------------------

// At γ=1 a few pinholes remain (62 of 1.57M rays on the tetrahedron: points of the
// tessellator's rings spaced just over a voxel apart); from γ=1.25 on there are none.
void expectGapFree(const test::TriangleSoup& soup, int resolution) {
    for (double gamma : {1.0, 2.0}) {
        const VoxelizeOptions o = optionsFor(Method::Tessellation, resolution, gamma);
        const VoxelizeResult r = voxelize(soup.view(), o);
        const VoxelizeResult conservative = conservativeVoxels(soup.view(), o);
        const WatertightReport rays = watertightness(soup.view(), r, conservative);
        std::printf("%zu triangles @%d γ=%g: %llu split triangles (n <= %llu), %llu points, watertight %.6f (%llu rays "
                    "fail)\n",
                    soup.triangles.size() / 3, resolution, gamma, (unsigned long long)tess(r).split_triangles,
                    (unsigned long long)tess(r).largest_split, (unsigned long long)tess(r).points, rays.share(),
                    (unsigned long long)(rays.rays - rays.passed));
        EXPECT_GT(tess(r).split_triangles, 0u);
        if (gamma == 1.0) {
            EXPECT_GE(rays.share(), 0.9999);
        } else {
            EXPECT_EQ(rays.passed, rays.rays);
        }
        EXPECT_EQ(countSum(r), tess(r).points);
        // Points on a triangle 512 voxels wide carry float rounding of ~3e-5 voxel.
        EXPECT_EQ(falseBeyondTouch(soup.view(), r, conservative, 1e-4), 0u);
    }
}

TEST(TessellationLarge, HugeTriangleAt512) {
    test::TriangleSoup soup;
    soup.add({0, 0, 0}, {1, 0.35, 0.8}, {0.15, 1, 0.45});
    expectGapFree(soup, 512);
}

TEST(TessellationLarge, TetrahedronAt512) {
    test::TriangleSoup soup;
    const std::array<double, 3> a{0, 0, 0}, b{1, 0.1, 0.2}, c{0.3, 1, 0.1}, d{0.2, 0.3, 1};
    soup.add(a, c, b);
    soup.add(a, b, d);
    soup.add(a, d, c);
    soup.add(b, c, d);
    expectGapFree(soup, 512);
}

// --- PN-triangles and displacement ----------------------------------------------------------

// An icosphere (icosahedron subdivided `levels` times, vertices pushed onto the unit sphere),
// with a spherical UV map.
test::TriangleSoup icosphere(int levels, std::vector<float>* uvs) {
    const double t = (1 + std::sqrt(5.0)) / 2;
    std::vector<std::array<double, 3>> v{{-1, t, 0}, {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                                         {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
    std::vector<std::array<int, 3>> f{{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                      {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                      {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                      {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    test::TriangleSoup icosahedron;
    for (const auto& p : v)
        for (double x : p) icosahedron.positions.push_back(float(x));
    for (const auto& tri : f)
        for (int i : tri) icosahedron.triangles.push_back(std::uint32_t(i));
    // Midpoint subdivision (shared edges shared), then every vertex onto the unit sphere.
    const Mesh fine = test::midpointSubdivide(icosahedron.view(), levels);
    test::TriangleSoup soup;
    soup.triangles = fine.triangles;
    v.clear();
    for (std::size_t i = 0; i < fine.vertexCount(); ++i) {
        const double x = fine.positions[3 * i], y = fine.positions[3 * i + 1], z = fine.positions[3 * i + 2];
        const double len = std::sqrt(x * x + y * y + z * z);
        v.push_back({x / len, y / len, z / len});
        for (double c : v.back()) soup.positions.push_back(float(c));
    }
    if (uvs)
        for (const auto& p : v) {
            uvs->push_back(float(0.5 + std::atan2(p[1], p[0]) / (2 * kPi)));
            uvs->push_back(float(0.5 + std::asin(std::clamp(p[2], -1.0, 1.0)) / kPi));
        }
    return soup;
}

// Mean distance of voxel centres to the unit sphere, in voxels.
double meanSphereDistance(const VoxelizeResult& r) {
    double sum = 0;
    const auto coords = r.occupancy.coords();
    for (const auto& c : coords) {
        const auto p = r.grid.voxelCentre(c[0], c[1], c[2]);
        sum += std::abs(std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) - 1.0);
    }
    return sum / double(coords.size()) / r.grid.voxel_size;
}

TEST(TessellationPn, LowPolySphereLandsCloserToTheSphere) {
    const test::TriangleSoup soup = icosphere(1, nullptr);  // 80 triangles
    VoxelizeOptions o = optionsFor(Method::Tessellation, 128, 2.0);
    o.grid.bounds = Bounds{{-1.02, -1.02, -1.02}, {1.02, 1.02, 1.02}};
    const VoxelizeResult flat = voxelize(soup.view(), o);
    o.tessellation.pn_triangles = true;
    const VoxelizeResult pn = voxelize(soup.view(), o);
    const double d_flat = meanSphereDistance(flat), d_pn = meanSphereDistance(pn);
    std::printf("icosphere(80) @128: mean distance to the sphere: flat %.3f, PN %.3f voxels\n", d_flat, d_pn);
    EXPECT_LT(d_pn, 0.5 * d_flat);
    EXPECT_LT(d_pn, 1.0);
    EXPECT_EQ(countSum(pn), tess(pn).points);
}

// Two triangles over the unit square at z = 0, UV = xy, normals +z.
struct FlatSquare {
    std::vector<float> positions{0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    std::vector<std::uint32_t> triangles{0, 1, 2, 0, 2, 3};
    std::vector<float> uvs{0, 0, 1, 0, 1, 1, 0, 1};
    MeshView view() const {
        MeshView v{positions.data(), 4, triangles.data(), 2};
        v.uvs = uvs.data();
        return v;
    }
};

TEST(TessellationDisplacement, FlatSquareFollowsASineHeightImage) {
    const FlatSquare square;
    // Heights vary along u only (two periods of a sine), so the expected height of a
    // voxel column is the same bilinear sample the CPU twin computes.
    HeightImage image{256, 4, {}};
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 256; ++x) image.values.push_back(float(0.5 + 0.5 * std::sin(4 * kPi * (x + 0.5) / 256)));
    VoxelizeOptions o = optionsFor(Method::Tessellation, 128, 1.0);
    o.grid.bounds = Bounds{{0, 0, -0.25}, {1, 1, 0.25}};
    o.tessellation.displacement_pixels = image;
    o.tessellation.displacement_strength = 0.3;  // world units: ±0.15 around z = 0 (midlevel 0.5)
    o.tessellation.displacement_midlevel = 0.5;
    const VoxelizeResult r = voxelize(square.view(), o);
    const double s = r.grid.voxel_size;
    const tessellation::DisplacementMap map(image);
    // Each voxel's centre must lie within one voxel (along z) of the displaced surface above
    // the voxel's footprint (sampled 9×9: the sine climbs up to ~1.9 voxels per voxel).
    double worst = 0;
    std::set<std::pair<int, int>> columns;
    for (const auto& c : r.occupancy.coords()) {
        const auto centre = r.grid.voxelCentre(c[0], c[1], c[2]);
        double nearest = 1e9;
        for (int a = 0; a <= 8; ++a)
            for (int b = 0; b <= 8; ++b) {
                const double x = centre[0] + (a / 8.0 - 0.5) * s, y = centre[1] + (b / 8.0 - 0.5) * s;
                nearest = std::min(nearest, std::abs(centre[2] - (test::sampleHeight(map, x, y) - 0.5) * 0.3) / s);
            }
        worst = std::max(worst, nearest);
        columns.insert({c[0], c[1]});
    }
    std::printf("sine displacement @128: %llu voxels, worst |z - height| %.3f voxels, %zu of %d columns\n",
                (unsigned long long)r.stats.voxel_count, worst, columns.size(), 128 * 128);
    EXPECT_LE(worst, 1.0);
    EXPECT_EQ(columns.size(), std::size_t(128 * 128));  // every column of the square has a point
    EXPECT_EQ(tess(r).points_clipped, 0u);
}

TEST(TessellationDisplacement, LowPolyPlusMapMatchesCpuSubdividedAndDisplaced) {
    std::vector<float> uvs;
    test::TriangleSoup soup = icosphere(1, &uvs);
    MeshView view = soup.view();
    view.uvs = uvs.data();
    HeightImage image{64, 32, {}};
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 64; ++x)
            image.values.push_back(float(0.5 + 0.5 * std::sin(2 * kPi * x / 16.0) * std::cos(2 * kPi * y / 16.0)));
    VoxelizeOptions o = optionsFor(Method::Tessellation, 128, 1.0);
    o.grid.bounds = Bounds{{-1.2, -1.2, -1.2}, {1.2, 1.2, 1.2}};
    o.tessellation.displacement_pixels = image;
    o.tessellation.displacement_strength = 0.2;
    o.tessellation.pn_triangles = true;
    // The same surface, subdivided on the CPU until its triangles are under half a voxel, and
    // voxelized exactly.
    const ValidatedMesh validated = validate(view);
    VoxelizeOptions exact = o;
    exact.method = Method::Cpu;
    const GridSpec grid = voxelize(view, exact).grid;  // the grid both runs share
    const Mesh dense = test::subdivideAndDisplace(validated, grid, o.tessellation, 96);
    const VoxelizeResult reference = voxelize(dense.view(), exact);
    // Stated bounds: the points sample the displaced surface like they sample a plain mesh,
    // so the bias against the conservative set behaves as on the real meshes (a little more
    // on a curved, displaced surface whose micro-triangles the displacement stretches) and
    // falls with γ; false voxels are the few where the piecewise-flat CPU surface and the
    // GPU's points round across a voxel face.
    const std::map<double, double> max_bias{{1.0, 0.35}, {4.0, 0.10}};
    for (const auto& [gamma, bound] : max_bias) {
        o.tessellation.gamma = gamma;
        const VoxelizeResult gpu = voxelize(view, o);
        ASSERT_EQ(gpu.grid.dims, grid.dims);
        const AccuracyReport acc = compareToReference(gpu.occupancy, reference.occupancy);
        const double false_share = double(acc.false_voxels) / double(gpu.stats.voxel_count);
        std::printf("displaced icosphere @128 γ=%g: GPU %llu voxels, CPU %llu; bias %.4f, false %.4f of the GPU's\n",
                    gamma, (unsigned long long)gpu.stats.voxel_count, (unsigned long long)reference.stats.voxel_count,
                    acc.bias, false_share);
        EXPECT_LE(acc.bias, bound);
        EXPECT_LE(false_share, 0.005);
    }
}

TEST(TessellationDisplacement, WholeTrianglesGetTheirDisplacedCentroid) {
    // A finely split square at a coarse grid: every triangle's factors are below 1, so the
    // compute pass injects one point per triangle. Expected: the centroid of its corners,
    // each displaced along +z by (height(uv) - midlevel) * strength, computed here in double.
    const FlatSquare square;
    Mesh fine = test::midpointSubdivide(square.view(), 5);  // 2048 triangles
    MeshView view = fine.view();
    view.uvs = fine.uvs.data();
    HeightImage image{16, 16, {}};
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) image.values.push_back(float(0.5 + 0.4 * std::sin(x * 0.9 + y * 0.4)));
    VoxelizeOptions o = optionsFor(Method::Tessellation, 16, 1.0);
    o.grid.bounds = Bounds{{0, 0, -0.3}, {1, 1, 0.3}};
    o.tessellation.displacement_pixels = image;
    o.tessellation.displacement_strength = 0.5;
    o.tessellation.displacement_midlevel = 0.5;
    const VoxelizeResult r = voxelize(view, o);
    ASSERT_EQ(tess(r).triangles_whole, fine.triangleCount());
    ASSERT_EQ(tess(r).points, fine.triangleCount());

    const tessellation::DisplacementMap map(image);
    std::map<std::array<std::int32_t, 3>, std::uint32_t> expected;
    for (std::size_t t = 0; t < fine.triangleCount(); ++t) {
        std::array<double, 3> centroid{0, 0, 0};
        for (int c = 0; c < 3; ++c) {
            const std::uint32_t v = fine.triangles[3 * t + c];
            const double height = (test::sampleHeight(map, fine.uvs[2 * v], fine.uvs[2 * v + 1]) - 0.5) * 0.5;
            const double p[3] = {fine.positions[3 * v], fine.positions[3 * v + 1], fine.positions[3 * v + 2] + height};
            for (int a = 0; a < 3; ++a) centroid[a] += p[a] / 3.0;
        }
        const std::array<double, 3> in_voxels = r.grid.toVoxel(centroid);
        std::array<std::int32_t, 3> voxel{};
        for (int a = 0; a < 3; ++a) voxel[a] = std::int32_t(std::floor(in_voxels[a]));
        ++expected[voxel];
    }
    std::map<std::array<std::int32_t, 3>, std::uint32_t> got;
    for (const auto& c : r.counts) got[{c.i, c.j, c.k}] = c.count;
    EXPECT_EQ(got, expected);
}

// --- options, stats and errors -------------------------------------------------------------

TEST(TessellationApi, CountsAreDeterministicAndAccuracyIsMeasured) {
    const test::TestMesh mesh = test::loadTestMesh(test::meshPath("dragon_stanford_res3_48k.ply"));
    VoxelizeOptions o = optionsFor(Method::Tessellation, 128, 2.0);
    const VoxelizeResult a = voxelize(mesh.view(), o);
    const VoxelizeResult b = voxelize(mesh.view(), o);
    ASSERT_EQ(a.counts.size(), b.counts.size());
    for (std::size_t i = 0; i < a.counts.size(); ++i) {
        ASSERT_EQ(a.counts[i].i, b.counts[i].i);
        ASSERT_EQ(a.counts[i].j, b.counts[i].j);
        ASSERT_EQ(a.counts[i].k, b.counts[i].k);
        ASSERT_EQ(a.counts[i].count, b.counts[i].count);
        ASSERT_TRUE(a.occupancy.test(a.counts[i].i, a.counts[i].j, a.counts[i].k));
    }
    // Accuracy is a utility the caller runs on the exact cpu voxels (hyvox/accuracy.h): its
    // figures against the same voxels counted here one by one.
    const VoxelizeResult conservative = conservativeVoxels(mesh.view(), o);
    VoxelizeOptions thin_options = o;
    thin_options.mode = Mode::Thin;
    thin_options.method = Method::Cpu;
    const VoxelizeResult thin = voxelize(mesh.view(), thin_options);
    std::uint64_t reference = 0, missed = 0, false_voxels = 0, thin_reference = 0, thin_missed = 0;
    const auto& dims = a.occupancy.dims();
    for (int i = 0; i < dims[0]; ++i)
        for (int j = 0; j < dims[1]; ++j)
            for (int k = 0; k < dims[2]; ++k) {
                const bool got = a.occupancy.test(i, j, k), want = conservative.occupancy.test(i, j, k);
                reference += want;
                missed += want && !got;
                false_voxels += got && !want;
                thin_reference += thin.occupancy.test(i, j, k);
                thin_missed += thin.occupancy.test(i, j, k) && !got;
            }
    ASSERT_GT(missed, 0u);  // γ=2 misses some: the bias below is not a trivial 0 = 0
    const AccuracyReport accuracy = compareToReference(a.occupancy, conservative.occupancy);
    EXPECT_EQ(accuracy.reference_voxels, reference);
    EXPECT_EQ(accuracy.missed_voxels, missed);
    EXPECT_EQ(accuracy.false_voxels, false_voxels);
    EXPECT_DOUBLE_EQ(accuracy.bias, double(missed) / double(reference));
    EXPECT_DOUBLE_EQ(compareToReference(a.occupancy, thin.occupancy).bias,
                     double(thin_missed) / double(thin_reference));
    // Binary only: the same bits without the count pool.
    o.tessellation.counts = false;
    const VoxelizeResult bits = voxelize(mesh.view(), o);
    EXPECT_TRUE(bits.counts.empty());
    EXPECT_TRUE(bits.occupancy == a.occupancy);
}

TEST(TessellationApi, PngDisplacementMatchesThePixelArray) {
    const FlatSquare square;
    const std::string path = (std::filesystem::temp_directory_path() / "hyvox_test_ramp.png").string();
    std::vector<png_byte> ramp;
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 64; ++x) ramp.push_back(png_byte(x * 4));
    png_image image{};
    image.version = PNG_IMAGE_VERSION;
    image.width = 64;
    image.height = 8;
    image.format = PNG_FORMAT_GRAY;
    ASSERT_TRUE(png_image_write_to_file(&image, path.c_str(), 0, ramp.data(), 0, nullptr)) << image.message;
    VoxelizeOptions o = optionsFor(Method::Tessellation, 64, 1.0);
    o.grid.bounds = Bounds{{0, 0, -0.2}, {1, 1, 0.45}};
    o.tessellation.displacement_image = path;
    o.tessellation.displacement_strength = 0.5;
    o.tessellation.displacement_midlevel = 0.25;
    const VoxelizeResult from_png = voxelize(square.view(), o);
    o.tessellation.displacement_image.clear();
    o.tessellation.displacement_pixels = HeightImage{64, 8, {}};
    for (png_byte v : ramp) o.tessellation.displacement_pixels.values.push_back(float(v) / 255.0f);
    const VoxelizeResult from_pixels = voxelize(square.view(), o);
    std::filesystem::remove(path);
    EXPECT_TRUE(from_png.occupancy == from_pixels.occupancy);
    EXPECT_EQ(tess(from_png).points_clipped, 0u);
    // The ramp climbs from (0 - 0.25) * 0.5 to (252/255 - 0.25) * 0.5 along x.
    const auto coords = from_png.occupancy.coords();
    int lowest = 1 << 30, highest = -1;
    for (const auto& c : coords) {
        if (c[0] == 0) lowest = std::min(lowest, c[2]);
        if (c[0] == 63) highest = std::max(highest, c[2]);
    }
    const double s = from_png.grid.voxel_size;
    EXPECT_NEAR((lowest + 0.5) * s + from_png.grid.origin[2], -0.125, 1.5 * s);
    EXPECT_NEAR((highest + 0.5) * s + from_png.grid.origin[2], (252.0 / 255 - 0.25) * 0.5, 1.5 * s);
}

TEST(TessellationApi, BadOptionsAreClearErrors) {
    const FlatSquare square;
    VoxelizeOptions o = optionsFor(Method::Tessellation, 32, 0.0);
    EXPECT_THROW(voxelize(square.view(), o), InvalidInput);
    o.tessellation.gamma = 1.0;
    o.tessellation.displacement_image = "/nonexistent/height.png";
    EXPECT_THROW(voxelize(square.view(), o), InvalidInput);
    o.tessellation.displacement_image.clear();
    o.tessellation.displacement_pixels = HeightImage{2, 2, {0, 1, 0, 1}};
    MeshView no_uvs = square.view();
    no_uvs.uvs = nullptr;
    EXPECT_THROW(voxelize(no_uvs, o), InvalidInput);
}

TEST(TessellationApi, ShaderFolderFromTheOptionsIsUsed) {
    // GlOptions::shader_dir reaches this method too: a copy of shaders/ whose point injection
    // does not compile gives a BackendError naming that file, and the unbroken copy on disk
    // gives the embedded shaders' voxels.
    const FlatSquare square;
    VoxelizeOptions o = optionsFor(Method::Tessellation, 32, 1.0);
    const test::TempDir temp;
    const std::filesystem::path dir = temp.path / "shaders";
    std::filesystem::copy(HYVOX_SOURCE_SHADERS, dir, std::filesystem::copy_options::recursive);
    std::ofstream(dir / "tessellation" / "inject.glsl", std::ios::app) << "\nthis is not glsl;\n";
    o.gl.shader_dir = dir.string();
    try {
        voxelize(square.view(), o);
        FAIL() << "expected BackendError";
    } catch (const BackendError& e) {
        EXPECT_NE(std::string(e.what()).find("tessellation/inject.glsl"), std::string::npos) << e.what();
    }
    o.gl.shader_dir = HYVOX_SOURCE_SHADERS;
    const SparseGrid from_disk = voxelize(square.view(), o).occupancy;
    EXPECT_EQ(from_disk.count(), 32u * 32u);  // the square lies in one layer of voxels
    o.gl.shader_dir = "";
    EXPECT_EQ(from_disk, voxelize(square.view(), o).occupancy);
}

TEST(TessellationApi, CancelStopsTheRunAndTheNextRunWorks) {
    const FlatSquare square;
    // Lets the planning milestone pass, then cancels at the first check between draws.
    struct CancelAfter : Interrupter {
        int calls = 0;
        bool wasInterrupted(int) override { return ++calls > 2; }
    } cancel;
    const VoxelizeOptions o = optionsFor(Method::Tessellation, 64, 1.0);
    EXPECT_THROW(voxelize(square.view(), o, &cancel), Cancelled);
    EXPECT_GT(cancel.calls, 2);
    const VoxelizeResult r = voxelize(square.view(), o);
    EXPECT_EQ(r.stats.voxel_count, 64u * 64u);  // the square lies in one layer of voxels
}

}  // namespace
}  // namespace hyvox
