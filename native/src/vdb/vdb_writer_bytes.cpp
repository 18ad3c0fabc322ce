// SPDX-License-Identifier: GPL-3.0-or-later
// The memory writeVdb holds beside the result (vdb_direct_writer.h), on its own: voxelize()'s
// memory estimate takes it without the writer (and the fuzz targets build it so).
#include "vdb/vdb_direct_writer.h"

#include <algorithm>
#include <cmath>

namespace hyvox::vdb {

double vdbWriterBytes(double leaves, double tile_bricks, double valued_voxels, double channels) {
    // Each grid's VdbLeaf per leaf (the density's and the attribute grids': colour, alpha and
    // normal, up to three channels each, all listed before the write); the placed tree's node
    // per leaf, twice while its tiles merge, and the leaf's index in write order; the density's
    // tile bricks listed one by one (a VdbTile), placed (a Placed, its value and flag) and placed
    // again while tiles merge into larger ones (a Placed), the attribute grids listing their
    // regions instead.
    constexpr double kListedLeaf = 40, kPlacedLeaf = 2 * 32 + 8, kListedTile = 32 + 2 * 32 + 13;
    constexpr double kDensityLeaf = 220, kMask = 64, kValue = 4;
    const double grids = 1.0 + std::ceil(channels / 3.0);
    // One batch of leaf buffers: a density leaf's, or an attribute leaf's mask and values
    // (uncompressed: colour need not compress), whichever grid is larger.
    const double per_leaf = leaves > 0 ? valued_voxels / leaves : 0.0;
    const double batch = std::min(leaves, double(kVdbLeavesPerBatch)) *
        std::max(kDensityLeaf, channels > 0 ? kMask + per_leaf * channels * kValue : 0.0);
    return (kListedLeaf * grids + kPlacedLeaf) * leaves + kListedTile * tile_bricks + batch;
}

}  // namespace hyvox::vdb
