// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// What a run will hold beside its mesh, estimated before any work from the mesh and the grid:
// the peak of each pass (the surface pass, the solid pass, the attribute values, the .vdb
// writer), each the sum of the buffers that pass holds at its fullest. voxelize() refuses a run
// whose largest pass exceeds the memory budget, naming the pass and the option; the stats
// report every pass (bench/bench_memory_estimate.py compares them with the peak resident
// memory of real runs: the estimate stays above it and within 1.5 times of it).
//
// The sizes come from the structures: a leaf is 72 bytes (brick index and 64 bytes of bits),
// a vector grown by doubling holds up to three times its final size while it moves (the
// surface's list of leaves, whose size is known closely, by a model of the allocator), a
// tile's bits are all touched (a surface crosses nearly every 2 MiB page of them), and the
// solid pass's trees take per triangle what their nodes do (fast winding numbers, ray
// columns). What the surface and the solid hold is unknown until they are made: the surface's
// leaves are counted on large grids (the mesh voxelized on the grid of the bricks) and
// estimated from the triangles' area in voxel units on small ones, its voxels from the area,
// the inside's bricks from the mesh's enclosed volume. The area and the volume are validate()'s
// sums (TriangleSums) scaled to the grid: only a region's run and the inside pass read the
// triangles again, for what depends on where they fall in the grid.
#include <cstdint>
#include <string>

#include "core/backends.h"
#include "hyvox/grid.h"
#include "hyvox/options.h"
#include "solid/edge_closure.h"
#include "tile_plan.h"

namespace hyvox::memory {

struct Estimate {
    // Bytes held at the fullest point of each pass (0 for a pass the run does not make).
    double surface = 0, solid = 0, attributes = 0, write = 0, sdf = 0;
    // What the mesh and the grid gave: the surface's leaves and voxels, the inside's bricks.
    double surface_leaves = 0, surface_voxels = 0, inside_bricks = 0;

    double peak() const;
    // "the surface pass", "the solid pass", "the attribute values", "the sdf" or "the .vdb
    // file": the largest, for a message.
    const char* largest() const;
};

// `channels`: the attribute channels per voxel (0 without attributes); `closure`: solid
// mode's and the sdf's edge check (it decides which trees the inside pass builds), null
// otherwise.
Estimate estimate(const ValidatedMesh& mesh, const GridSpec& grid, const VoxelizeOptions& options,
                  const tiling::TilePlan& plan, int channels, const solid::EdgeClosure* closure);

// ResourceError before any work when the estimate's largest pass exceeds the budget.
void checkBudget(const Estimate& estimate, const GridSpec& grid, const VoxelizeOptions& options);

}  // namespace hyvox::memory
