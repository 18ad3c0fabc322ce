// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Attribute voxels of one tile from pieces a method clipped itself (the GL methods clip on
// the GPU): the same definition and the same code as computeTileAttributes (docs/design.md,
// "Attributes"). Each voxel sums its pieces in the order of their triangles, as the cpu
// method does, so the result does not depend on the order the GPU appended them in.
#include <vector>

#include "attributes/surface_values.h"
#include "attributes/tile_attributes.h"
#include "core/backends.h"

namespace hyvox::attributes {

// `pieces` hold every (voxel, triangle) pair of the tile whose voxel is set in
// `bits`; a set voxel with none gets zeros and is counted as unreached.
TileAttributeCounts computePieceAttributes(const BackendJob& job, const BitGrid& bits, const SurfaceValues& values,
                                           const std::vector<VoxelPiece>& pieces, std::vector<AttributeLeaf>& out);

}  // namespace hyvox::attributes
