// SPDX-License-Identifier: GPL-3.0-or-later
// The GL methods (triangle, fragment, hybrid) on every shared mesh against the oracles:
// conservative = the brute-force `reference` up to touches within 1e-5 voxel, with no holes;
// thin = the `cpu` thin voxelizer up to touches; thin of closed meshes is 6-separating.
// They run on llvmpipe (Mesa's software EGL device) where there is no GPU, and never skip.
#include <gtest/gtest.h>

#include <iostream>
#include <ostream>
#include <string>
#include <vector>

#include "support/test_mesh_loader.h"
#include "support/triangle_soup.h"
#include "support/voxel_checks.h"

namespace hyvox {
namespace {

constexpr Method kGlMethods[] = {Method::Triangle, Method::Fragment, Method::Hybrid};

VoxelizeOptions optionsFor(Method method, Mode mode, int resolution) {
    VoxelizeOptions o;
    o.method = method;
    o.mode = mode;
    o.grid.resolution = resolution;
    o.hybrid.cutoff = 4.0;  // a few voxel units², as the paper suggests; auto is tested apart
    return o;
}

// Every GL method against the oracle on one mesh, both modes.
void checkMesh(const MeshView& mesh, int resolution, const std::string& label) {
    for (Mode mode : {Mode::Conservative, Mode::Thin}) {
        const Method oracle_method = mode == Mode::Conservative ? Method::Reference : Method::Cpu;
        const VoxelizeResult oracle = voxelize(mesh, optionsFor(oracle_method, mode, resolution));
        for (Method method : kGlMethods) {
            SCOPED_TRACE(label + " @" + std::to_string(resolution) + " " + toString(method) + " " + toString(mode));
            const VoxelizeResult result = voxelize(mesh, optionsFor(method, mode, resolution));
            const auto cmp = test::compareResults(mesh, mode, result, oracle);
            test::expectMatchesOracle(cmp);             // touches: at most 7 per case on llvmpipe
            if (cmp.result_only + cmp.oracle_only > 0)  // touches are counted, and shown
                std::cout << "  " << label << " @" << resolution << " " << toString(method) << " " << toString(mode)
                          << ": " << cmp.summary() << "\n";
            if (method == Method::Hybrid) {
                ASSERT_TRUE(result.stats.hybrid.has_value());
                EXPECT_EQ(result.stats.hybrid->cutoff, 4.0);
            }
            if (mode == Mode::Conservative) {
                std::uint64_t samples = 0;
                std::vector<std::array<double, 3>> holes;
                EXPECT_EQ(test::countHoles(mesh, result, &samples, &holes), 0u) << "of " << samples << " samples";
                EXPECT_GT(samples, 0u);
            }
        }
    }
}

struct MeshCase {
    std::string file;
    int resolution;
};
// Without it GoogleTest prints the case as raw bytes ("40-byte object <F0-31 ...>").
void PrintTo(const MeshCase& c, std::ostream* os) { *os << c.file << " @" << c.resolution; }

class GlMeshTest : public ::testing::TestWithParam<MeshCase> {};

TEST_P(GlMeshTest, MatchesOraclesInBothModes) {
    const test::TestMesh mesh = test::loadTestMesh(test::meshPath(GetParam().file));
    checkMesh(mesh.view(), GetParam().resolution, GetParam().file);
}

std::vector<MeshCase> meshCases() {
    std::vector<MeshCase> cases;
    for (const std::string& file : test::sharedMeshFiles())
        for (int resolution : {64, 128}) cases.push_back({file, resolution});
    cases.push_back({"bunny_stanford_69k.ply", 256});
    cases.push_back({"sponza_crytek_262k_vcolor.ply.gz", 256});
    return cases;
}

std::string caseName(const ::testing::TestParamInfo<MeshCase>& info) {
    return test::meshCaseName(info.param.file, info.param.resolution);
}

INSTANTIATE_TEST_SUITE_P(SharedMeshes, GlMeshTest, ::testing::ValuesIn(meshCases()), caseName);

TEST(GlMeshes, TheSharedMeshesAreThere) {
    // The suite runs on test::sharedMeshFiles(): it must be the folder's listing (as in
    // CpuVsReference.MeshListIsComplete), or meshes would be skipped silently.
    EXPECT_EQ(test::listMeshFiles(), test::sharedMeshFiles()) << "HYVOX_MESH_DIR=" << test::meshDir();
}

// The pathological case of section 3.2: one triangle spanning the whole scene.
TEST(GlMeshes, SceneSpanningTriangleAt256) {
    test::TriangleSoup soup;
    soup.add({0.0, 0.0, 0.0}, {1.0, 0.37, 0.11}, {0.23, 1.0, 0.91});
    checkMesh(soup.view(), 256, "scene-spanning triangle");
}

// Thin voxelizations of closed meshes leave no 6-connected path from outside to inside.
TEST(GlMeshes, ThinIsSixSeparatingOnClosedMeshes) {
    for (const auto& [file, resolution] :
         {std::pair<std::string, int>{"spot_vcolor.ply", 64}, {"armadillo_52k.ply", 96}}) {
        const test::TestMesh mesh = test::loadTestMesh(test::meshPath(file));
        for (Method method : kGlMethods) {
            SCOPED_TRACE(file + " " + toString(method));
            VoxelizeOptions o = optionsFor(method, Mode::Thin, resolution);
            o.grid.padding = 1;
            test::expectSixSeparating(mesh.view(), voxelize(mesh.view(), o), 1000);
        }
    }
}

}  // namespace
}  // namespace hyvox
