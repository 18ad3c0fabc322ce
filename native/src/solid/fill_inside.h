// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Solid mode's inside pass: the voxels whose centre is inside the mesh and that are not
// already in the (exact conservative) surface, by the options' inside rule.
//
// The voxels are not tested one by one. No triangle meets a voxel outside the conservative
// surface, so the segment between two such voxels' centres, through voxels outside it, never
// crosses the surface, and the inside value can change along it only by the amount the open
// edges allow (solid/gradient_bound.h). Hence:
//  - a box of whole bricks that holds no surface voxel is decided by one test at its middle
//    when the value there is farther from the threshold than the bound allows over the box
//    (always, for a closed mesh); otherwise it is split, down to single bricks;
//  - in a brick with surface, each 6-connected part of its other voxels is decided by one test
//    when the bound over the part's longest path allows it;
//  - everything else is tested voxel by voxel.
// Decided boxes become tiles (runs of whole bricks), so memory follows the surface.
// Why it is built this way, and what an open mesh costs: docs/why/solid.md.
#include <cstddef>

#include "hyvox/interrupter.h"
#include "hyvox/mesh.h"
#include "hyvox/options.h"
#include "hyvox/result.h"
#include "hyvox/sparse_grid.h"
#include "solid/edge_closure.h"

namespace hyvox::solid {

// `surface`: the conservative surface of the whole grid, or of the box of options.region
// (finished; the inside is then decided in that box only). Returns the inside voxels
// (finished; disjoint from `surface` apart from tiles, which may cover surface voxels), and
// fills `stats` (all but tile_bricks). With `surface_inside`, also decides the centres of the
// surface's own voxels by the same rule (the sign of the sdf attribute, which the occupancy
// does not need) and stores those inside there (finished; a subset of `surface`). A centre
// lying on the surface itself (distance 0) may go either way.
SparseGrid fillInside(const ValidatedMesh& mesh, const GridSpec& grid, const SparseGrid& surface,
                      const VoxelizeOptions& options, Interrupter* interrupter, SolidStats& stats,
                      SparseGrid* surface_inside = nullptr);
// How an open mesh's winding numbers are sampled (solid/winding_less_crossings.h): from the
// open edges' sheets or the fast winding tree, by the rule (bySheets), or forced (the tests
// and bench/bench_open_sampling compare the two).
enum class OpenSampling { Rule, Tree, Sheets };
// Whether the rule samples an open mesh with `open_edges` open edges from their sheets.
bool bySheets(std::size_t open_edges, std::size_t triangles);

// The same with the mesh's edge check already made (the dispatcher makes it before any work:
// it decides which trees this pass builds, and so what memory it needs).
SparseGrid fillInside(const ValidatedMesh& mesh, const GridSpec& grid, const SparseGrid& surface,
                      const VoxelizeOptions& options, const EdgeClosure& closure, Interrupter* interrupter,
                      SolidStats& stats, SparseGrid* surface_inside = nullptr,
                      OpenSampling sampling = OpenSampling::Rule);

// Whether the inside is decided by ray crossings alone (parity, or auto on a mesh whose edges
// all cancel); else by fast winding numbers (with the rays' integer part near open edges).
bool insideByRays(const EdgeClosure& closure, const VoxelizeOptions& options);

}  // namespace hyvox::solid
