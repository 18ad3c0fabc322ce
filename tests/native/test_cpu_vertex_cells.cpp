// SPDX-License-Identifier: GPL-3.0-or-later
// The cpu method's integer first look (src/cpu/vertex_cells.h) runs only when triangles share
// their vertices (at most 1.5 vertices per triangle); a triangle soup of the same triangles
// takes the per-corner setup instead. Meshes of sub-voxel triangles whose vertices lie on
// voxel planes, edges and corners, and just beside them: the shared mesh must give exactly
// the soup's voxels and the brute-force reference's, conservative and thin, also when the
// grid clips the mesh; and a flat patch lying on a voxel plane its known answer.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "support/triangle_soup.h"
#include "support/voxel_checks.h"

namespace hyvox::test {
namespace {

// A heightfield of (n x n) quads, 2 triangles each, sharing (n+1)^2 vertices; the lattice
// spacing is `step` voxels from `origin`. z(i, j) is chosen so that some vertices lie
// exactly on voxel planes (whole numbers) and others a float step beside them.
struct SharedMesh {
    std::vector<float> positions;
    std::vector<std::uint32_t> triangles;
    MeshView view() const { return viewOf(positions, triangles); }
    TriangleSoup soup() const {
        TriangleSoup s;
        auto p = [&](std::uint32_t v) {
            return std::array<double, 3>{positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]};
        };
        for (std::size_t t = 0; t < triangles.size(); t += 3)
            s.add(p(triangles[t]), p(triangles[t + 1]), p(triangles[t + 2]));
        return s;
    }
};

SharedMesh heightfield(int n, double step, double origin, double (*z)(int, int)) {
    SharedMesh m;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i)
            for (double c : {origin + i * step, origin + j * step, z(i, j)}) m.positions.push_back(float(c));
    auto at = [&](int i, int j) { return std::uint32_t(j * (n + 1) + i); };
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            m.triangles.insert(m.triangles.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            m.triangles.insert(m.triangles.end(), {at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    return m;
}

// Whole numbers (voxel planes) on every third row, just above / below them (one float ulp
// at 4) on others, and a slow wave elsewhere: triangles within one voxel, straddling one
// plane, or two.
double bumpy(int i, int j) {
    if (j % 3 == 0) return 4.0;
    if (i % 5 == 1) return std::nextafter(4.0f, 5.0f);
    if (i % 5 == 2) return std::nextafter(4.0f, 3.0f);
    return 4.0 + 0.45 * std::sin(0.37 * i) * std::cos(0.23 * j);
}
double flat(int, int) { return 3.0; }

VoxelizeResult run(const MeshView& mesh, const GridOptions& grid, Mode mode, Method method = Method::Cpu) {
    VoxelizeOptions options;
    options.grid = grid;
    options.mode = mode;
    options.method = method;
    return voxelize(mesh, options);
}

TEST(CpuVertexCells, SharedVerticesGiveTheSoupsAndTheReferencesVoxels) {
    // Lattice steps of 1/4 voxel (vertices on voxel planes every 4th) and 0.3 (never), from
    // a whole-voxel origin and from a fractional one; a grid holding the mesh, and one whose
    // bounds cut it (the candidates are clipped).
    for (double step : {0.25, 0.3})
        for (double origin : {1.0, 1.37}) {
            const SharedMesh mesh = heightfield(48, step, origin, bumpy);
            const TriangleSoup soup = mesh.soup();
            for (const GridOptions& grid : {unitGrid(20), unitGrid(8)})
                for (Mode mode : {Mode::Conservative, Mode::Thin}) {
                    const VoxelizeResult shared = run(mesh.view(), grid, mode);
                    EXPECT_EQ(sortedVoxels(shared), sortedVoxels(run(soup.view(), grid, mode)))
                        << "step " << step << " origin " << origin << " grid " << grid.bounds->max[0] << " "
                        << toString(mode);
                    const Comparison cmp =
                        compareResults(mesh.view(), mode, shared, run(mesh.view(), grid, mode, Method::Reference));
                    expectMatchesOracle(cmp);
                    EXPECT_EQ(cmp.result_only + cmp.oracle_only, 0u) << cmp.summary();
                }
        }
}

TEST(CpuVertexCells, PatchOnAVoxelPlaneMarksBothLayers) {
    // Sub-voxel triangles in the plane z = 3 over x, y in [1, 7]: every closed box of the
    // layers z = 2 and z = 3 whose column meets [1, 7]^2 (columns 0..7) touches it.
    const SharedMesh mesh = heightfield(24, 0.25, 1.0, flat);
    VoxelList expected;
    for (int i = 0; i <= 7; ++i)
        for (int j = 0; j <= 7; ++j)
            for (int k : {2, 3}) expected.push_back({i, j, k});
    EXPECT_EQ(sortedVoxels(run(mesh.view(), unitGrid(10), Mode::Conservative)), expected);
    EXPECT_EQ(sortedVoxels(run(mesh.view(), unitGrid(10), Mode::Conservative, Method::Reference)), expected);
}

}  // namespace
}  // namespace hyvox::test
