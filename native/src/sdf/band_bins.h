// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Which triangles may lie within the band of which blocks of 32³ voxels (4³ bricks): for each
// triangle, the blocks that hold a voxel centre closer than the band to its bounding box, less
// (for triangles that reach more than a few blocks: Sponza's floors and walls) those whose
// centres all lie farther than the band from the triangle itself. Grouped by block (CSR),
// blocks ascending: a block's distances are then computed by one thread from its own list,
// without atomics, each triangle set up once for the block. A small triangle reaches one or two
// blocks where it would reach four to eight bricks.
#include <array>
#include <cstdint>
#include <vector>

#include "hyvox/grid.h"
#include "hyvox/interrupter.h"
#include "hyvox/mesh.h"

namespace hyvox::sdf {

// The blocks of a grid: (x * ny + y) * nz + z over the block counts, as BrickLayout numbers bricks.
struct BlockLayout {
    static constexpr int kLog2 = 5;
    static constexpr int kSide = 1 << kLog2;  // voxels
    std::array<std::int32_t, 3> counts{0, 0, 0};
    explicit BlockLayout(const GridSpec& grid) {
        for (int a = 0; a < 3; ++a) counts[a] = (grid.dims[a] + kSide - 1) >> kLog2;
    }
    std::uint64_t index(int x, int y, int z) const {
        return (std::uint64_t(x) * std::uint64_t(counts[1]) + std::uint64_t(y)) * std::uint64_t(counts[2]) +
            std::uint64_t(z);
    }
    std::array<std::int32_t, 3> at(std::uint64_t index) const {
        const std::uint64_t nz = std::uint64_t(counts[2]), ny = std::uint64_t(counts[1]);
        return {std::int32_t(index / (nz * ny)), std::int32_t((index / nz) % ny), std::int32_t(index % nz)};
    }
};

struct BandBins {
    std::vector<std::uint64_t> blocks;     // BlockLayout indices, ascending
    std::vector<std::uint64_t> start;      // blocks.size() + 1 offsets into `triangles`
    std::vector<std::uint32_t> triangles;  // mesh triangle indices, block by block
    std::size_t byteSize() const { return blocks.capacity() * 8 + start.capacity() * 8 + triangles.capacity() * 4; }
};

// The voxel-space corners of triangle t.
std::array<std::array<double, 3>, 3> voxelCorners(const ValidatedMesh& mesh, const GridSpec& grid, std::uint32_t t);

// The voxels (inclusive index ranges, clipped to the grid) whose centres lie within `band`
// voxels of the box of `corners`; false when there are none.
bool reachOf(const std::array<std::array<double, 3>, 3>& corners, const GridSpec& grid, double band,
             std::array<std::int32_t, 3>& lo, std::array<std::int32_t, 3>& hi);

// `budget_bytes`: what the bins may take (ResourceError naming the budget when they would not
// fit, before they are made); `interrupter` is asked as the triangles go.
BandBins binBand(const ValidatedMesh& mesh, const GridSpec& grid, double band, std::uint64_t budget_bytes,
                 std::uint64_t budget_mib, Interrupter* interrupter);

}  // namespace hyvox::sdf
