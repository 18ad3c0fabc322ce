// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The contract between the dispatcher (src/voxelize/) and each backend. The dispatcher has
// checked the options, validated the mesh, laid out the grid and allocated result.occupancy
// (dims = grid.dims); a backend sets bits in it, may fill result.counts, and adds its own
// timings and its typed section of the stats (Stats::cpu, ::reference, ::hybrid,
// ::tessellation). Geometry outside the grid is clipped by the backend, never wrapped.
// Backends neither include nor call one another.
#include "hyvox/interrupter.h"
#include "hyvox/mesh.h"
#include "hyvox/options.h"
#include "hyvox/result.h"

namespace hyvox {

struct BackendJob {
    const ValidatedMesh& mesh;
    const GridSpec& grid;
    const VoxelizeOptions& options;
    Interrupter* interrupter;  // may be null
};

void runCpuBackend(const BackendJob& job, VoxelizeResult& result);           // src/cpu/
void runReferenceBackend(const BackendJob& job, VoxelizeResult& result);     // src/reference/
void runHybridBackend(const BackendJob& job, VoxelizeResult& result);        // src/hybrid/: triangle|fragment|hybrid
void runTessellationBackend(const BackendJob& job, VoxelizeResult& result);  // src/tessellation/

}  // namespace hyvox
