// SPDX-License-Identifier: GPL-3.0-or-later
// The memory writeVdb holds beside the result (vdb_direct_writer.h), on its own: voxelize()'s
// memory estimate takes it without the writer (and the fuzz targets build it so).
#include "io/vdb_direct_writer.h"

namespace hyvox::io {

double vdbWriterBytes(double leaves, double tile_bricks, double valued_voxels, double channels) {
    // A VdbLeaf and its node in the placed tree; the density's tile bricks listed one by one (a
    // VdbTile), placed (a Placed, its value and flag) and placed again while tiles merge into
    // larger ones (a Placed), the attribute grids listing their regions instead.
    constexpr double kListedLeaf = 32 + 24, kListedTile = 32 + 2 * 32 + 13;
    constexpr double kDensityLeaf = 220, kMask = 64, kValue = 4;
    const double grids = channels > 0 ? 2.0 : 1.0;  // the attribute grids share one set of leaves
    const double file = kDensityLeaf * leaves + 2.0 * tile_bricks +
        (channels > 0 ? kMask * leaves + valued_voxels * channels * kValue : 0.0);
    return kListedLeaf * leaves * grids + kListedTile * tile_bricks + 2.0 * file;
}

}  // namespace hyvox::io
