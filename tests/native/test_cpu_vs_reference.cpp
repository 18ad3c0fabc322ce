// SPDX-License-Identifier: GPL-3.0-or-later
// The cpu voxelizer must produce exactly the brute-force reference's voxel set on every
// shared mesh, conservative and thin; the only allowed differences are voxels that merely
// touch a triangle within 1e-5 voxel units (decided, and counted, by the reference's
// eps-grown / eps-shrunk rule).
#include <gtest/gtest.h>

#include <string>
#include <tuple>
#include <vector>

#include "support/gtest_printers.h"
#include "support/test_mesh_loader.h"
#include "support/voxel_checks.h"

namespace hyvox::test {
namespace {

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
    expectMatchesOracle(cmp);
}

// The one guard on the shared mesh list (every mesh suite runs on sharedMeshFiles()): it fails
// if a mesh is added to or removed from ../shared/data/meshes, so none is skipped silently.
TEST(CpuVsReference, MeshListIsComplete) {
    ASSERT_FALSE(meshDir().empty()) << "HYVOX_MESH_DIR is not set";
    EXPECT_EQ(listMeshFiles(), sharedMeshFiles());
}

using Case = std::tuple<std::string, int, Mode>;
class EveryMesh : public ::testing::TestWithParam<Case> {};

TEST_P(EveryMesh, EqualsReference) {
    const auto& [file, resolution, mode] = GetParam();
    expectEqualToReference(file, resolution, mode);
}

std::string caseName(const ::testing::TestParamInfo<Case>& info) {
    return meshCaseName(std::get<0>(info.param), std::get<1>(info.param)) + "_" + toString(std::get<2>(info.param));
}

INSTANTIATE_TEST_SUITE_P(At64And128, EveryMesh,
                         ::testing::Combine(::testing::ValuesIn(sharedMeshFiles()), ::testing::Values(64, 128),
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
