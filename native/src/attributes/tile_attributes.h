// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Attribute voxels of one tile: for every voxel a method set, the weighted mean over the
// triangles whose closed box meets it (docs/design.md, "Attributes"). Sums and weights are
// accumulated in double per region of 4³ leaves, one region per task, each region's
// triangles in the mesh's order: the result does not depend on the thread count.
#include <cstdint>
#include <vector>

#include "attributes/clip_to_voxel.h"
#include "attributes/surface_values.h"
#include "core/attribute_leaf.h"
#include "core/backends.h"

namespace hyvox::attributes {

struct TileAttributeCounts {
    std::uint64_t pieces = 0;            // (triangle, voxel) pairs clipped to a non-empty piece
    std::uint64_t voxels_unreached = 0;  // set voxels no clipped piece reached, even with the margin (value 0)
    std::uint64_t leaves_rounded = 0;    // leaves where the kTouchMargin fallback ran
};

// Triangle `triangle` of the mesh in the whole grid's voxel space, in double: the corners every
// piece's barycentrics are taken on.
std::array<Point, 3> triangleCorners(const BackendJob& job, std::uint32_t triangle);

// brute_force (the reference method): every region scans all the tile's triangles instead of
// the ones binned to it.
TileAttributeCounts computeTileAttributes(const BackendJob& job, const BitGrid& bits, const SurfaceValues& values,
                                          bool brute_force, std::vector<AttributeLeaf>& out);

// Puts the leaves of all tiles in brick order (the order of SparseGrid::finish) and
// concatenates their values into grid.values, on `threads` threads (0: all); a block that
// holds them all in that order becomes grid.values as it is.
void assembleAttributes(std::vector<AttributeLeaf>& leaves, AttributeGrid& grid, int threads);

}  // namespace hyvox::attributes
