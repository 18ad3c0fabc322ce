// SPDX-License-Identifier: GPL-3.0-or-later
// The 'reference' method: for every usable triangle, test every voxel of its clipped
// bounding box with the oracle's overlap rule. Slow on purpose (no factoring, no
// shortcuts); parallel over triangles only so the test suite stays quick.
#include <algorithm>
#include <atomic>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "core/backends.h"
#include "core/stopwatch.h"
#include "reference/reference_overlap.h"

namespace hyvox {

void runReferenceBackend(const BackendJob& job, TileOutput& out, Stats& stats) {
    Stopwatch watch;
    const auto& usable = job.mesh.usable;
    BitGrid& grid = out.bits;
    const Tile& tile = job.tile;
    std::atomic<std::size_t> done{0};
    std::atomic<std::uint64_t> tests{0};

    const int threads = job.options.threads > 0 ? job.options.threads : tbb::task_arena::automatic;
    tbb::task_arena arena(threads);
    arena.execute([&] {
        tbb::parallel_for(
            tbb::blocked_range<std::size_t>(0, usable.size(), 256), [&](const tbb::blocked_range<std::size_t>& chunk) {
                throwIfInterrupted(job.interrupter, int(100 * done.load() / std::max<std::size_t>(usable.size(), 1)));
                std::uint64_t local_tests = 0;
                for (std::size_t t = chunk.begin(); t != chunk.end(); ++t) {
                    const auto tri = reference::voxelSpaceTriangle(job.mesh, usable[t], job.grid);
                    auto range = reference::candidateVoxels(tri, job.grid.dims);
                    for (int a = 0; a < 3; ++a) {  // the tile's part
                        range.lo[a] = std::max(range.lo[a], tile.offset[a]);
                        range.hi[a] = std::min(range.hi[a], tile.last(a));
                    }
                    if (range.empty()) continue;
                    for (int i = range.lo[0]; i <= range.hi[0]; ++i)
                        for (int j = range.lo[1]; j <= range.hi[1]; ++j)
                            for (int k = range.lo[2]; k <= range.hi[2]; ++k) {
                                ++local_tests;
                                if (reference::overlaps(tri, {i, j, k}, job.options.mode))
                                    grid.setAtomic(i - tile.offset[0], j - tile.offset[1], k - tile.offset[2]);
                            }
                }
                tests += local_tests;
                done += chunk.size();
            });
    });
    stats.addTiming("voxelize", watch.elapsedMs());
    if (!stats.reference) stats.reference.emplace();
    stats.reference->voxel_tests += tests.load();
}

}  // namespace hyvox
