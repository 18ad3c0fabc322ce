// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The voxel grid convention shared by every backend (see DESIGN.md, "Coordinates"):
// voxel (i,j,k) covers the closed box [origin + (i,j,k)·s, origin + (i+1,j+1,k+1)·s].
// Shaders and voxelizers work in voxel space p' = (p - origin) / s.
#include <array>
#include <cstdint>
#include <optional>

#include "hyvox/mesh.h"

namespace hyvox {

struct GridSpec {
    std::array<double, 3> origin{0, 0, 0};  // world position of voxel (0,0,0)'s min corner
    double voxel_size = 1.0;                 // world units per voxel edge
    std::array<std::int32_t, 3> dims{1, 1, 1};

    std::uint64_t voxelCount() const {
        return std::uint64_t(dims[0]) * std::uint64_t(dims[1]) * std::uint64_t(dims[2]);
    }
    // World position of voxel (i,j,k)'s centre (OpenVDB's index-space convention).
    std::array<double, 3> voxelCentre(int i, int j, int k) const {
        return {origin[0] + (i + 0.5) * voxel_size, origin[1] + (j + 0.5) * voxel_size,
                origin[2] + (k + 0.5) * voxel_size};
    }
};

struct GridOptions {
    int resolution = 256;                   // voxels along the longest side (ignored if voxel_size)
    std::optional<double> voxel_size;       // world units; overrides resolution
    std::optional<std::array<double, 3>> origin;  // default: mesh bounds min (minus padding)
    std::optional<Bounds> bounds;           // default: mesh bounds; geometry outside is clipped
    int padding = 0;                        // empty voxels added on every side
};

constexpr int kMaxResolution = 16384;

// Applies the convention: origin = bounds min (unless given), s = longest extent / resolution
// (unless given), dims = ceil(extent / s) per axis, at least 1. Throws InvalidInput for a
// resolution or voxel size out of range or a zero-extent mesh without a voxel size.
GridSpec makeGrid(const Bounds& mesh_bounds, const GridOptions& options);

}  // namespace hyvox
