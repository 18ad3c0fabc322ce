// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Small hand-built meshes for known-answer tests, a unit grid to voxelize them on, and the
// voxel set of a result as a sorted list for exact comparisons.
#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "hyvox/voxelize.h"
#include "support/mesh_arrays.h"

namespace hyvox::test {

struct TriangleSoup {
    std::vector<float> positions;
    std::vector<std::uint32_t> triangles;

    void add(const std::array<double, 3>& a, const std::array<double, 3>& b, const std::array<double, 3>& c) {
        for (const auto* p : {&a, &b, &c}) {
            triangles.push_back(std::uint32_t(positions.size() / 3));
            for (double x : *p) positions.push_back(float(x));
        }
    }
    // An axis-aligned box [lo, hi] as 12 triangles (outward winding).
    void addBox(const std::array<double, 3>& lo, const std::array<double, 3>& hi) {
        auto corner = [&](int bits) {
            return std::array<double, 3>{bits & 1 ? hi[0] : lo[0], bits & 2 ? hi[1] : lo[1], bits & 4 ? hi[2] : lo[2]};
        };
        const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
        for (const auto& q : quads) {
            add(corner(q[0]), corner(q[1]), corner(q[2]));
            add(corner(q[0]), corner(q[2]), corner(q[3]));
        }
    }
    MeshView view() const { return viewOf(positions, triangles); }
};

// A grid with voxel (i,j,k) = world [i,i+1]x[j,j+1]x[k,k+1] * size, dims n^3, whatever the
// mesh: voxel size `size`, origin 0, bounds [0, n * size]^3.
inline GridOptions unitGrid(int n, double size = 1.0) {
    GridOptions g;
    g.voxel_size = size;
    g.origin = std::array<double, 3>{0, 0, 0};
    g.bounds = Bounds{{0, 0, 0}, {n * size, n * size, n * size}};
    return g;
}

using VoxelList = std::vector<std::array<std::int32_t, 3>>;

inline VoxelList sortedVoxels(const VoxelizeResult& result) {
    VoxelList v = result.occupancy.coords();
    std::sort(v.begin(), v.end());
    return v;
}

}  // namespace hyvox::test
