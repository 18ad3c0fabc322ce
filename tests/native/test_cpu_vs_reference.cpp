// SPDX-License-Identifier: GPL-3.0-or-later
// The cpu voxelizer must produce exactly the brute-force reference's voxel set on every
// shared mesh, conservative and thin; the only allowed differences are voxels that merely
// touch a triangle within 1e-5 voxel units (decided, and counted, by the reference's
// eps-grown / eps-shrunk rule).
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <tuple>
#include <vector>

#include "support/gtest_printers.h"
#include "support/test_mesh_loader.h"
#include "support/voxel_checks.h"

namespace hyvox::test {
namespace {

// Every mesh of ../shared/data/meshes (the listing test below fails if one is added or
// removed, so none can be skipped silently).
const std::vector<std::string> kMeshes = {
    "armadillo_52k.ply",          "bunny_stanford_69k.ply",   "dragon_stanford_871k.ply.gz",
    "dragon_stanford_res2_203k.ply.gz", "dragon_stanford_res3_48k.ply", "elephant_holes.ply",
    "happy_buddha_100k.ply",      "igea_cyberware_268k.ply.gz", "shark_holes.ply",
    "spider_messy.ply",           "sponza_crytek_262k_vcolor.ply.gz", "spot_uv.ply",
    "spot_vcolor.ply",            "teapot_utah.ply",
};

const TestMesh& cachedMesh(const std::string& file) {
    static std::vector<TestMesh> cache;
    for (const TestMesh& m : cache)
        if (m.name == file) return m;
    if (cache.size() >= 2) cache.erase(cache.begin());  // big meshes: keep memory modest
    cache.push_back(loadTestMesh(meshPath(file)));
    return cache.back();
}

void expectEqualToReference(const std::string& file, int resolution, Mode mode) {
    const TestMesh& mesh = cachedMesh(file);
    VoxelizeOptions options;
    options.grid.resolution = resolution;
    options.mode = mode;
    const Comparison cmp = compareWithReference(mesh.view(), options);
    std::printf("[ compare  ] %s @%d %s: %s\n", file.c_str(), resolution, toString(mode), cmp.summary().c_str());
    EXPECT_GT(cmp.oracle_voxels, 0u);
    EXPECT_TRUE(cmp.unexplained.empty()) << cmp.summary() << "; first unexplained voxel (" << cmp.unexplained[0][0]
                                         << "," << cmp.unexplained[0][1] << "," << cmp.unexplained[0][2] << ")";
    // Touches are rare: a handful per mesh, never a systematic difference.
    EXPECT_LE(cmp.touches, std::max<std::uint64_t>(10, cmp.oracle_voxels / 10000)) << cmp.summary();
}

TEST(CpuVsReference, MeshListIsComplete) {
    ASSERT_FALSE(meshDir().empty()) << "HYVOX_MESH_DIR is not set";
    EXPECT_EQ(listMeshFiles(), kMeshes);
}

using Case = std::tuple<std::string, int, Mode>;
class EveryMesh : public ::testing::TestWithParam<Case> {};

TEST_P(EveryMesh, EqualsReference) {
    const auto& [file, resolution, mode] = GetParam();
    expectEqualToReference(file, resolution, mode);
}

std::string caseName(const ::testing::TestParamInfo<Case>& info) {
    std::string name = std::get<0>(info.param);
    name = name.substr(0, name.find('.'));
    std::replace_if(name.begin(), name.end(), [](char c) { return !std::isalnum(static_cast<unsigned char>(c)); }, '_');
    return name + "_" + std::to_string(std::get<1>(info.param)) + "_" + toString(std::get<2>(info.param));
}

INSTANTIATE_TEST_SUITE_P(At64And128, EveryMesh,
                         ::testing::Combine(::testing::ValuesIn(kMeshes), ::testing::Values(64, 128),
                                            ::testing::Values(Mode::Conservative, Mode::Thin)),
                         caseName);

INSTANTIATE_TEST_SUITE_P(At256, EveryMesh,
                         ::testing::Combine(::testing::Values("bunny_stanford_69k.ply",
                                                              "sponza_crytek_262k_vcolor.ply.gz"),
                                            ::testing::Values(256),
                                            ::testing::Values(Mode::Conservative, Mode::Thin)),
                         caseName);

}  // namespace
}  // namespace hyvox::test
