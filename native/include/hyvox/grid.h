// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file
/// The voxel grid convention shared by every backend (see docs/design.md, "Coordinates"):
/// voxel (i,j,k) covers the closed box [origin + (i,j,k)·s, origin + (i+1,j+1,k+1)·s].
/// Shaders and voxelizers work in voxel space p' = (p - origin) / s. The formulas of the
/// grid (to voxel space, sides, the 8³ bricks of the bit layout) are written here once.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "hyvox/mesh.h"

namespace hyvox {

/// The 8³ bricks (OpenVDB leaves) that cover a grid of voxels, in the order of the bit
/// layout (hyvox/bit_grid.h): brick (bx,by,bz) is number (bx·ny + by)·nz + bz.
struct BrickLayout {
    static constexpr int kLog2 = 3;               ///< log2 of kSide
    static constexpr int kSide = 8;               ///< voxels along a brick's side
    std::array<std::int32_t, 3> counts{0, 0, 0};  ///< bricks per axis: ceil(dims / 8)

    /// The bricks over a grid of `dims` voxels.
    static BrickLayout over(const std::array<std::int32_t, 3>& dims) {
        BrickLayout layout;
        for (int a = 0; a < 3; ++a) layout.counts[a] = (dims[a] + kSide - 1) >> kLog2;
        return layout;
    }
    /// The number of bricks.
    std::size_t total() const { return std::size_t(counts[0]) * std::size_t(counts[1]) * std::size_t(counts[2]); }
    /// The number of brick (bx,by,bz), 0 .. total() - 1.
    std::size_t index(int bx, int by, int bz) const {
        return (std::size_t(bx) * std::size_t(counts[1]) + std::size_t(by)) * std::size_t(counts[2]) + std::size_t(bz);
    }
    /// The brick of voxel (i,j,k).
    std::size_t indexOfVoxel(int i, int j, int k) const { return index(i >> kLog2, j >> kLog2, k >> kLog2); }
    /// The brick (bx,by,bz) of number `index`: index()'s inverse.
    std::array<std::int32_t, 3> at(std::size_t index) const {
        const std::size_t nz = std::size_t(counts[2]), ny = std::size_t(counts[1]);
        return {std::int32_t(index / (nz * ny)), std::int32_t((index / nz) % ny), std::int32_t(index % nz)};
    }
};

/// A laid-out grid (makeGrid): voxel (i,j,k) covers the closed box
/// [origin + (i,j,k)·voxel_size, origin + (i+1,j+1,k+1)·voxel_size], world units.
struct GridSpec {
    std::array<double, 3> origin{0, 0, 0};      ///< world position of voxel (0,0,0)'s min corner
    double voxel_size = 1.0;                    ///< world units per voxel edge
    std::array<std::int32_t, 3> dims{1, 1, 1};  ///< voxels along x, y, z

    /// Voxels in the whole box.
    std::uint64_t voxelCount() const {
        return std::uint64_t(dims[0]) * std::uint64_t(dims[1]) * std::uint64_t(dims[2]);
    }
    /// Voxels along the longest axis.
    std::int32_t maxSide() const { return std::max({dims[0], dims[1], dims[2]}); }
    std::string dimsText() const;  ///< "64x16x8", for messages
    /// World position of voxel (i,j,k)'s centre (OpenVDB's index-space convention).
    std::array<double, 3> voxelCentre(int i, int j, int k) const {
        return {origin[0] + (i + 0.5) * voxel_size, origin[1] + (j + 0.5) * voxel_size,
                origin[2] + (k + 0.5) * voxel_size};
    }
    /// A world point in voxel space, p' = (p - origin) / s, in double: every backend and test
    /// computes it this one way, so they all round a vertex alike.
    std::array<double, 3> toVoxel(const std::array<double, 3>& world) const {
        return {(world[0] - origin[0]) / voxel_size, (world[1] - origin[1]) / voxel_size,
                (world[2] - origin[2]) / voxel_size};
    }
    /// toVoxel() of a float position (a mesh vertex), widened to double first.
    std::array<double, 3> toVoxel(const std::array<float, 3>& world) const {
        return toVoxel(std::array<double, 3>{double(world[0]), double(world[1]), double(world[2])});
    }
    /// The 8³ bricks over the grid.
    BrickLayout bricks() const { return BrickLayout::over(dims); }
};

/// How voxelize() lays out its grid (the schema's "grid" options).
struct GridOptions {
    int resolution = 256;                         ///< voxels along the longest side (ignored if voxel_size)
    std::optional<double> voxel_size;             ///< world units; overrides resolution
    std::optional<std::array<double, 3>> origin;  ///< default: mesh bounds min (minus padding)
    std::optional<Bounds> bounds;                 ///< default: mesh bounds; geometry outside is clipped
    int padding = 0;                              ///< empty voxels added on every side
    /// Origin (unless given) at floor(bounds min / voxel size) whole voxel sizes, at or below
    /// the min: a lattice fixed in world space, so calls whose bounds differ (frames, Live
    /// edits) share their voxels where the mesh is the same.
    bool snap_origin = false;
};

/// The most voxels along any axis of a grid.
constexpr int kMaxResolution = 16384;

/// Lays out the grid by the convention: origin = bounds min (unless given; snapped down to a
/// whole multiple of s with snap_origin), s = longest extent /
/// resolution (unless given), dims = ceil(extent / s) per axis, at least 1; padding voxels
/// added on every side. Pure (thread-safe).
/// @param mesh_bounds the mesh's bounds (ValidatedMesh::bounds), world units
/// @param options the grid options (world units, voxels)
/// @throws InvalidInput an option outside the schema's limits (hyvox/option_schema.h, the same
///         message voxelize() gives), a zero-extent mesh without a voxel size, more than
///         kMaxResolution voxels along an axis, bounds whose sides overflow a double, or a voxel
///         more than a million times the mesh's longest side (the mesh a speck the GPU
///         methods' single precision loses)
GridSpec makeGrid(const Bounds& mesh_bounds, const GridOptions& options);

}  // namespace hyvox
