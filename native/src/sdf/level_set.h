// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The sdf attribute of a run (hyvox/level_set.h): the band's exact distances (band_bins.h,
// band_distances.h) signed by the inside pass's answer at each voxel centre, with the inside
// beyond the band as inactive leaves and tiles.
#include <cstdint>

#include "hyvox/interrupter.h"
#include "hyvox/level_set.h"
#include "hyvox/mesh.h"
#include "hyvox/options.h"
#include "hyvox/result.h"
#include "hyvox/sparse_grid.h"

namespace hyvox::sdf {

// Which voxel centres are inside, as solid::fillInside decides them (all finished): the exact
// conservative surface it ran on, those of its voxels whose centre is inside, and the voxels
// off it whose centre is inside.
struct InsideCentres {
    const SparseGrid& surface;
    const SparseGrid& surface_inside;
    const SparseGrid& inside;
};

// `held_bytes`: what the run holds already, counted against options' memory budget with the
// sdf's own bins and leaves (ResourceError before they are made when they would not fit).
// Runs on options.threads; `interrupter` is asked as it goes (hyvox::Cancelled).
LevelSetGrid makeLevelSet(const ValidatedMesh& mesh, const GridSpec& grid, const InsideCentres& centres,
                          const VoxelizeOptions& options, std::uint64_t held_bytes, Interrupter* interrupter,
                          SdfStats& stats);

}  // namespace hyvox::sdf
