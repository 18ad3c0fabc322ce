// SPDX-License-Identifier: GPL-3.0-or-later
// The dispatcher: checks the options against the schema, validates the mesh, lays out the
// grid, and hands the job to the method's backend (core/backends.h).
#include "hyvox/voxelize.h"

#include <string>

#include "core/backends.h"
#include "core/stopwatch.h"
#include "hyvox/option_schema.h"

namespace hyvox {
namespace {

void checkMemoryBudget(const GridSpec& grid, const VoxelizeOptions& options) {
    // Refuse before allocating: the bit grid is padded to whole 8³ bricks.
    const std::uint64_t bytes = std::uint64_t(grid.bricks().total()) * BitGrid::kWordsPerBrick * sizeof(std::uint64_t);
    if (bytes > options.memoryBudgetBytes())
        throw ResourceError("a " + grid.dimsText() + " grid needs " + std::to_string(bytes >> 20) +
                            " MiB of bits, more than the memory budget of " +
                            std::to_string(options.memory_budget_mib) + " MiB; use a larger voxel size");
}

}  // namespace

VoxelizeResult voxelize(const MeshView& mesh, const VoxelizeOptions& options, Interrupter* interrupter) {
    checkOptions(options);
    if (interrupter) interrupter->start("hyvox voxelize");
    struct EndOnExit {
        Interrupter* i;
        ~EndOnExit() {
            if (i) i->end();
        }
    } end_on_exit{interrupter};

    VoxelizeResult result;
    result.stats.options = options;
    Stopwatch watch;
    const ValidatedMesh validated = validate(mesh);
    result.grid = makeGrid(validated.bounds, options.grid);
    checkMemoryBudget(result.grid, options);
    result.stats.addTiming("validate", watch.restart());
    throwIfInterrupted(interrupter, 0);

    result.occupancy = BitGrid(result.grid.dims);
    result.stats.addTiming("allocate", watch.restart());

    result.stats.method = toString(options.method);
    result.stats.mode = toString(options.mode);
    result.stats.triangles_input = mesh.triangle_count;
    result.stats.triangles_used = validated.usable.size();
    result.stats.triangles_degenerate = validated.degenerate_count;

    const BackendJob job{validated, result.grid, options, interrupter};
    switch (options.method) {
        case Method::Cpu: runCpuBackend(job, result); break;
        case Method::Reference: runReferenceBackend(job, result); break;
        case Method::Triangle:
        case Method::Fragment:
        case Method::Hybrid: runHybridBackend(job, result); break;
        case Method::Tessellation: runTessellationBackend(job, result); break;
    }
    throwIfInterrupted(interrupter, 100);
    watch.restart();
    result.stats.voxel_count = result.occupancy.count();
    result.stats.addTiming("count", watch.restart());
    return result;
}

}  // namespace hyvox
