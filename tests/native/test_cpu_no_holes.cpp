// SPDX-License-Identifier: GPL-3.0-or-later
// No holes, ever: every point of every triangle lies in the closed box of at least one voxel
// of the conservative cpu output (dense barycentric samples, vertices and edges included).
// The 1e-9 slack only absorbs the samples' own double rounding; it is far below the 1e-5
// touch tolerance, which never excuses a hole.
#include <gtest/gtest.h>

#include <string>
#include <tuple>
#include <vector>

#include "support/test_mesh_loader.h"
#include "support/triangle_soup.h"
#include "support/voxel_checks.h"

namespace hyvox::test {
namespace {

void expectNoHoles(const MeshView& mesh, const VoxelizeOptions& options, const std::string& what) {
    const VoxelizeResult result = voxelize(mesh, options);
    std::uint64_t samples = 0;
    std::vector<std::array<double, 3>> first;
    const std::uint64_t holes = countHoles(mesh, result, &samples, &first);
    std::printf("[ holes    ] %s: %llu samples, %llu holes\n", what.c_str(), static_cast<unsigned long long>(samples),
                static_cast<unsigned long long>(holes));
    EXPECT_GT(samples, 0u);
    EXPECT_EQ(holes, 0u) << what << ": first hole at voxel-space (" << (first.empty() ? 0 : first[0][0]) << ", "
                         << (first.empty() ? 0 : first[0][1]) << ", " << (first.empty() ? 0 : first[0][2]) << ")";
}

using Case = std::tuple<std::string, int>;
class MeshHoles : public ::testing::TestWithParam<Case> {};

TEST_P(MeshHoles, EverySurfacePointIsCovered) {
    const auto& [file, resolution] = GetParam();
    const TestMesh mesh = loadTestMesh(meshPath(file));
    VoxelizeOptions options;
    options.grid.resolution = resolution;
    expectNoHoles(mesh.view(), options, file + " @" + std::to_string(resolution));
}

// Every shared mesh once (at 128, dragon res2 and igea at 64), bunny and sponza also at 256.
std::vector<Case> meshCases() {
    std::vector<Case> cases;
    for (const std::string& file : sharedMeshFiles()) {
        const bool coarse = file == "dragon_stanford_res2_203k.ply.gz" || file == "igea_cyberware_268k.ply.gz";
        cases.push_back({file, coarse ? 64 : 128});
        if (file == "bunny_stanford_69k.ply" || file == "sponza_crytek_262k_vcolor.ply.gz")
            cases.push_back({file, 256});
    }
    return cases;
}

std::string caseName(const ::testing::TestParamInfo<Case>& info) {
    return meshCaseName(std::get<0>(info.param), std::get<1>(info.param));
}

INSTANTIATE_TEST_SUITE_P(SharedMeshes, MeshHoles, ::testing::ValuesIn(meshCases()), caseName);

TEST(NoHoles, FacesOnVoxelPlanes) {
    // A box whose size is a multiple of the voxel size: every face lies on voxel planes.
    TriangleSoup box;
    box.addBox({0, 0, 0}, {3, 2, 5});
    VoxelizeOptions options;
    options.grid.voxel_size = 0.25;
    expectNoHoles(box.view(), options, "box 3x2x5 at voxel size 1/4");
    options.grid.padding = 2;
    expectNoHoles(box.view(), options, "box 3x2x5 at voxel size 1/4, padded");

    // A single triangle lying exactly on the voxel plane z = 2, and its rotations.
    for (int w = 0; w < 3; ++w) {
        std::array<double, 3> a{1, 1, 1}, b{1, 1, 1}, c{1, 1, 1};
        a[w] = b[w] = c[w] = 2;
        b[(w + 1) % 3] = 7;
        c[(w + 2) % 3] = 6;
        TriangleSoup tri;
        tri.add(a, b, c);
        VoxelizeOptions on_plane;
        on_plane.grid = unitGrid(8);
        expectNoHoles(tri.view(), on_plane, "triangle on plane axis " + std::to_string(w));
    }
}

TEST(NoHoles, ClippedGeometryLeavesNoHolesInsideTheGrid) {
    // Bounds smaller than the mesh: what lies inside the grid is still fully covered.
    const TestMesh bunny = loadTestMesh(meshPath("bunny_stanford_69k.ply"));
    const ValidatedMesh v = validate(bunny.view());
    VoxelizeOptions options;
    options.grid.resolution = 96;
    Bounds inner = v.bounds;
    for (int a = 0; a < 3; ++a) {
        const double extent = v.bounds.max[a] - v.bounds.min[a];
        inner.min[a] += 0.3 * extent;
        inner.max[a] -= 0.2 * extent;
    }
    options.grid.bounds = inner;
    expectNoHoles(bunny.view(), options, "bunny clipped to an inner box");
}

}  // namespace
}  // namespace hyvox::test
