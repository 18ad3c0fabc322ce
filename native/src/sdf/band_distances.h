// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// One block's distances: for each of its 32³ voxels, the least squared distance (voxel units) from
// its centre to the block's triangles (BandBins), where that is below band²; band² where none
// comes nearer. A block crowded with triangles smaller than a voxel measures those by queries
// (band_queries.h) and sweeps the rest. A swept triangle is measured only along the rows of the
// block its band can reach, and along each row over the stretch inside the slab of half-width band
// around its plane, lengthened to whole quads (four voxels): every distance of the stretch is
// computed, four at a time, without a test per voxel (a test that skipped the voxels a nearer
// triangle had already claimed cost more than the distances it saved, as short rows ran scalar
// remainders).
#include <cstdint>

#include "hyvox/grid.h"
#include "hyvox/mesh.h"
#include "sdf/band_bins.h"
#include "sdf/band_queries.h"

namespace hyvox::sdf {

constexpr int kBlockVoxels = BlockLayout::kSide * BlockLayout::kSide * BlockLayout::kSide;

// The voxel (x, y, z) of a block (each 0..31) at x * 1024 + y * 32 + z.
inline int blockOffset(int x, int y, int z) { return (x * BlockLayout::kSide + y) * BlockLayout::kSide + z; }

// The block's bricks (4 along each axis) as the bits of one word, (bx * 4 + by) * 4 + bz.
constexpr int kBlockBricks = BlockLayout::kSide / BrickLayout::kSide;
static_assert(kBlockBricks * kBlockBricks * kBlockBricks == 64, "a block's bricks are the bits of one word");
inline int brickBit(int bx, int by, int bz) { return (bx * kBlockBricks + by) * kBlockBricks + bz; }

// A block's small triangles go to the queries when there are at least this many for each cell
// they lie in, on average: a lower threshold queries blocks too sparse to gain from it, a
// higher one sweeps crowded blocks that the queries do faster (docs/why/sdf.md).
constexpr double kQueriedFrom = 4.0;

// Block `number` of `bins` into `d2` (kBlockVoxels values); adds the distances computed to
// `evaluations`. Returns the bricks where a distance was computed (elsewhere d2 is band²).
// `queries`: the calling thread's, or null to sweep every triangle; `queried_from`: when the
// block's small triangles go to them (0: whenever there are any).
std::uint64_t blockDistances(const ValidatedMesh& mesh, const GridSpec& grid, double band, const BandBins& bins,
                             std::size_t number, double* d2, std::uint64_t& evaluations, BlockQueries* queries,
                             double queried_from = kQueriedFrom);

}  // namespace hyvox::sdf
