// SPDX-License-Identifier: GPL-3.0-or-later
// Thin (6-separating) output of a closed mesh must separate inside from outside: no
// 6-connected path of empty voxels joins a voxel whose centre is inside the mesh (ray
// parity, an oracle independent of both voxelizers) to the grid boundary.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <string>
#include <vector>

#include "support/test_mesh_loader.h"
#include "support/triangle_soup.h"

namespace hyvox::test {
namespace {

// inside[(i*dy + j)*dz + k]: is the point (i+1/2, j+1/2+dy', k+1/2+dz') inside the mesh, by the
// parity of a ray along +x? The tiny irrational offsets keep the rays off mesh edges and
// vertices; they move the point by far less than a voxel, so an empty voxel's answer is
// that of its centre (a surface passing between them would have marked the voxel).
std::vector<char> insideByParity(const MeshView& mesh, const GridSpec& grid) {
    const int nx = grid.dims[0], ny = grid.dims[1], nz = grid.dims[2];
    const double oy = 0.5 + 1.1e-6 * std::sqrt(2.0), oz = 0.5 + 0.7e-6 * std::sqrt(3.0);
    std::vector<std::vector<double>> crossings(std::size_t(ny) * nz);
    const ValidatedMesh v = validate(mesh);
    for (std::uint32_t t : v.usable) {
        double p[3][3];
        for (int c = 0; c < 3; ++c) {
            const auto q = v.vertex(t, c);
            for (int a = 0; a < 3; ++a) p[c][a] = (double(q[a]) - grid.origin[a]) / grid.voxel_size;
        }
        const double ymin = std::min({p[0][1], p[1][1], p[2][1]}), ymax = std::max({p[0][1], p[1][1], p[2][1]});
        const double zmin = std::min({p[0][2], p[1][2], p[2][2]}), zmax = std::max({p[0][2], p[1][2], p[2][2]});
        for (int j = std::max(0, int(std::floor(ymin - oy))); j <= std::min(ny - 1, int(std::ceil(ymax - oy))); ++j)
            for (int k = std::max(0, int(std::floor(zmin - oz))); k <= std::min(nz - 1, int(std::ceil(zmax - oz))); ++k) {
                const double y = j + oy, z = k + oz;
                // Point in the projected (y,z) triangle: all edge functions of one sign.
                double e[3];
                for (int c = 0; c < 3; ++c) {
                    const double* a = p[c];
                    const double* b = p[(c + 1) % 3];
                    e[c] = (b[1] - a[1]) * (z - a[2]) - (b[2] - a[2]) * (y - a[1]);
                }
                const bool in = (e[0] > 0 && e[1] > 0 && e[2] > 0) || (e[0] < 0 && e[1] < 0 && e[2] < 0);
                if (!in) continue;
                const double area = e[0] + e[1] + e[2];
                // Barycentric interpolation of x at the hit.
                const double x = (e[1] * p[0][0] + e[2] * p[1][0] + e[0] * p[2][0]) / area;
                crossings[std::size_t(j) * nz + k].push_back(x);
            }
    }
    std::vector<char> inside(std::size_t(nx) * ny * nz, 0);
    for (int j = 0; j < ny; ++j)
        for (int k = 0; k < nz; ++k) {
            auto& xs = crossings[std::size_t(j) * nz + k];
            std::sort(xs.begin(), xs.end());
            std::size_t passed = 0;
            for (int i = 0; i < nx; ++i) {
                while (passed < xs.size() && xs[passed] < i + 0.5) ++passed;
                inside[(std::size_t(i) * ny + j) * nz + k] = char(passed % 2);
            }
        }
    return inside;
}

struct Separation {
    std::uint64_t reached = 0;          // empty voxels 6-connected to the boundary
    std::uint64_t inside_empty = 0;     // empty voxels with an inside centre
    std::uint64_t inside_reached = 0;   // ... that the flood reached: must be 0
};

Separation floodFromBoundary(const BitGrid& bits, const std::vector<char>& inside) {
    const auto d = bits.dims();
    auto id = [&](int i, int j, int k) { return (std::size_t(i) * d[1] + j) * d[2] + k; };
    const std::size_t count = std::size_t(d[0]) * d[1] * d[2];
    std::vector<char> seen(count, 0);
    std::deque<std::array<int, 3>> queue;
    for (int i = 0; i < d[0]; ++i)
        for (int j = 0; j < d[1]; ++j)
            for (int k = 0; k < d[2]; ++k) {
                const bool boundary = i == 0 || j == 0 || k == 0 || i == d[0] - 1 || j == d[1] - 1 || k == d[2] - 1;
                if (boundary && !bits.test(i, j, k)) {
                    seen[id(i, j, k)] = 1;
                    queue.push_back({i, j, k});
                }
            }
    const int steps[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    while (!queue.empty()) {
        const auto p = queue.front();
        queue.pop_front();
        for (const auto& s : steps) {
            const int i = p[0] + s[0], j = p[1] + s[1], k = p[2] + s[2];
            if (!bits.inside(i, j, k) || seen[id(i, j, k)] || bits.test(i, j, k)) continue;
            seen[id(i, j, k)] = 1;
            queue.push_back({i, j, k});
        }
    }
    Separation out;
    for (int i = 0; i < d[0]; ++i)
        for (int j = 0; j < d[1]; ++j)
            for (int k = 0; k < d[2]; ++k) {
                if (bits.test(i, j, k)) continue;
                const bool in = inside[id(i, j, k)];
                out.reached += seen[id(i, j, k)];
                out.inside_empty += in;
                out.inside_reached += in && seen[id(i, j, k)];
            }
    return out;
}

class ThinSeparates : public ::testing::TestWithParam<std::tuple<std::string, int>> {};

TEST_P(ThinSeparates, InsideIsNotReachedFromTheBoundary) {
    const auto& [file, resolution] = GetParam();
    const TestMesh mesh = loadTestMesh(meshPath(file));
    VoxelizeOptions options;
    options.grid.resolution = resolution;
    options.grid.padding = 1;  // an empty layer all around, so the outside is connected
    options.mode = Mode::Thin;
    const VoxelizeResult result = voxelize(mesh.view(), options);
    const std::vector<char> inside = insideByParity(mesh.view(), result.grid);
    const Separation s = floodFromBoundary(result.occupancy, inside);
    std::printf("[ separate ] %s @%d thin: %llu voxels, %llu empty reached, %llu empty inside, %llu inside reached\n",
                file.c_str(), resolution, static_cast<unsigned long long>(result.stats.voxel_count),
                static_cast<unsigned long long>(s.reached), static_cast<unsigned long long>(s.inside_empty),
                static_cast<unsigned long long>(s.inside_reached));
    EXPECT_GT(s.reached, 0u);
    EXPECT_GT(s.inside_empty, 0u) << "the mesh should enclose empty voxels";
    EXPECT_EQ(s.inside_reached, 0u) << "a 6-connected path of empty voxels leaks into the inside";

    // Negative control: the same check must notice a leak when one slab of the surface is
    // removed (otherwise it would prove nothing).
    BitGrid cut = result.occupancy;
    BitGrid open(cut.dims());
    const int mid = cut.dims()[0] / 2;
    for (const auto& c : cut.coords())
        if (c[0] != mid) open.set(c[0], c[1], c[2]);
    EXPECT_GT(floodFromBoundary(open, inside).inside_reached, 0u);
}

INSTANTIATE_TEST_SUITE_P(WatertightMeshes, ThinSeparates,
                         ::testing::Values(std::tuple{"spot_vcolor.ply", 64}, std::tuple{"spot_vcolor.ply", 128},
                                           std::tuple{"armadillo_52k.ply", 128},
                                           std::tuple{"happy_buddha_100k.ply", 128},
                                           std::tuple{"igea_cyberware_268k.ply.gz", 96}));

TEST(ThinSeparation, UnitCube) {
    TriangleSoup cube;
    cube.addBox({0, 0, 0}, {1, 1, 1});
    VoxelizeOptions options;
    options.grid.resolution = 10;
    options.grid.padding = 1;
    options.mode = Mode::Thin;
    const VoxelizeResult result = voxelize(cube.view(), options);
    const Separation s = floodFromBoundary(result.occupancy, insideByParity(cube.view(), result.grid));
    EXPECT_EQ(s.inside_reached, 0u);
    EXPECT_GT(s.inside_empty, 0u);
}

}  // namespace
}  // namespace hyvox::test
