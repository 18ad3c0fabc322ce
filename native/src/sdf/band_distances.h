// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// One block's distances: for each of its 32³ voxels, the least squared distance (voxel units)
// from its centre to the block's triangles (BandBins), where that is below band²; band² where
// none comes nearer. Each triangle is measured only along the rows of the block its band can
// reach; along each row only over the voxels inside both the triangle's bounding sphere and
// the slab around its plane, each grown by the band; and of those only at the voxels it may
// come nearer to than the nearest triangle found so far (its sphere and its plane bound the
// distance from below), so that where triangles are small and many most of them cost a bound
// and not a distance.
#include <cstdint>

#include "hyvox/grid.h"
#include "hyvox/mesh.h"
#include "sdf/band_bins.h"

namespace hyvox::sdf {

constexpr int kBlockVoxels = BlockLayout::kSide * BlockLayout::kSide * BlockLayout::kSide;

// The voxel (x, y, z) of a block (each 0..31) at x * 1024 + y * 32 + z.
inline int blockOffset(int x, int y, int z) { return (x * BlockLayout::kSide + y) * BlockLayout::kSide + z; }

// Block `number` of `bins` into `d2` (kBlockVoxels values); adds the distances computed to
// `evaluations`.
void blockDistances(const ValidatedMesh& mesh, const GridSpec& grid, double band, const BandBins& bins,
                    std::size_t number, double* d2, std::uint64_t& evaluations);

}  // namespace hyvox::sdf
