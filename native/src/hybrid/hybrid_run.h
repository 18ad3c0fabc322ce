// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The hybrid backend's run, below runHybridBackend: also the entry point for the voxel list
// (section 3.5) and for benchmarks that want the pass timings.
#include <array>
#include <cstdint>
#include <vector>

#include "core/backends.h"
#include "hybrid/gl_voxelizer.h"

namespace hyvox::hybrid {

struct HybridRun {
    PassTimes times;
    double cutoff = 0;    // hybrid: used cutoff; triangle: inf; fragment: 0
    int search_runs = 0;  // timed runs of the auto-cutoff search (0: given or cached)
    double prepare_ms = 0, upload_ms = 0, search_ms = 0, voxelize_ms = 0;
};

// Runs job.options.method (triangle | fragment | hybrid) on the GL worker. Writes the bit
// grid into `out` (dims = job.grid.dims) or, when voxel_list is given, fills that instead
// (each set voxel once, unordered; `out` is then untouched). With `pieces`, also appends the
// clipped piece of every (voxel, triangle) pair (GlVoxelizer::runPieces).
HybridRun runHybrid(const BackendJob& job, BitGrid* out, std::vector<std::array<std::int32_t, 3>>* voxel_list = nullptr,
                    std::vector<VoxelPiece>* pieces = nullptr);

}  // namespace hyvox::hybrid
