// SPDX-License-Identifier: GPL-3.0-or-later
// The 'cpu' method: every triangle's factored test, in parallel over chunks of triangles
// with TBB. Bits are set with relaxed atomic ORs on whole words (no locks). A triangle
// covering many columns of its dominant plane is split by rows into tasks of its own, so
// one big wall cannot leave a core idle. Small triangles take shortcuts that decide the
// same voxels (triangle_setup.h, rasterize_small.h).
#include <algorithm>
#include <atomic>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "core/backends.h"
#include "core/stopwatch.h"
#include "cpu/mark_voxels.h"
#include "cpu/rasterize_planeless.h"
#include "cpu/rasterize_small.h"
#include "cpu/rasterize_triangle.h"
#include "cpu/triangle_setup.h"

namespace hyvox {
namespace {

// Columns of the dominant plane above which a triangle's rows become separate tasks.
constexpr long kSplitColumns = 64 * 64;
constexpr int kRowsPerTask = 8;
constexpr std::size_t kTrianglesPerChunk = 1024;

void rasterizeRowsAnyAxis(const cpu::TriangleSetup& t, int row_begin, int row_end, cpu::WordMarker& marker) {
    switch (t.w) {
        case 0: cpu::rasterizeRows<0>(t, row_begin, row_end, marker); break;
        case 1: cpu::rasterizeRows<1>(t, row_begin, row_end, marker); break;
        default: cpu::rasterizeRows<2>(t, row_begin, row_end, marker); break;
    }
}

}  // namespace

void runCpuBackend(const BackendJob& job, TileOutput& out, Stats& stats) {
    Stopwatch watch;
    const ValidatedMesh& mesh = job.mesh;
    const auto& usable = mesh.usable;
    const GridSpec& spec = job.grid;
    BitGrid& grid = out.bits;
    const std::array<std::int32_t, 3>& offset = job.tile.offset;
    const std::array<std::int32_t, 3> last{job.tile.last(0), job.tile.last(1), job.tile.last(2)};
    const Mode mode = job.options.mode;
    std::atomic<std::size_t> done{0};
    std::atomic<std::uint64_t> split_triangles{0};

    const int threads = job.options.threads > 0 ? job.options.threads : tbb::task_arena::automatic;
    tbb::task_arena arena(threads);
    arena.execute([&] {
        tbb::parallel_for(
            tbb::blocked_range<std::size_t>(0, usable.size(), kTrianglesPerChunk),
            [&](const tbb::blocked_range<std::size_t>& chunk) {
                throwIfInterrupted(job.interrupter,
                                   int(100 * done.load(std::memory_order_relaxed) / std::max<std::size_t>(usable.size(), 1)));
                cpu::WordMarker marker(grid, offset);
                for (std::size_t n = chunk.begin(); n != chunk.end(); ++n) {
                    const std::array<std::array<double, 3>, 3> corners{spec.toVoxel(mesh.vertex(usable[n], 0)),
                                                                       spec.toVoxel(mesh.vertex(usable[n], 1)),
                                                                       spec.toVoxel(mesh.vertex(usable[n], 2))};
                    cpu::TriangleSetup t;
                    const cpu::SetupKind kind = cpu::setupTriangle(corners, mode, offset, last, t);
                    if (kind == cpu::SetupKind::Outside) continue;
                    if (kind == cpu::SetupKind::AllCandidates) {
                        for (int i = t.lo[0]; i <= t.hi[0]; ++i)
                            for (int j = t.lo[1]; j <= t.hi[1]; ++j)
                                for (int k = t.lo[2]; k <= t.hi[2]; ++k) marker.mark(i, j, k);
                        continue;
                    }
                    if (kind == cpu::SetupKind::Planeless) {
                        cpu::rasterizePlaneless(corners, mode, t.lo, t.hi, marker);
                        continue;
                    }
                    if (cpu::fitsSmallPath(t)) {
                        cpu::rasterizeSmall(t, marker);
                        continue;
                    }
                    const int rows = t.hi[1] - t.lo[1] + 1;
                    const long columns = long(rows) * (t.hi[0] - t.lo[0] + 1);
                    if (columns <= kSplitColumns) {
                        rasterizeRowsAnyAxis(t, t.lo[1], t.hi[1] + 1, marker);
                        continue;
                    }
                    split_triangles.fetch_add(1, std::memory_order_relaxed);
                    tbb::parallel_for(tbb::blocked_range<int>(t.lo[1], t.hi[1] + 1, kRowsPerTask),
                                      [&](const tbb::blocked_range<int>& r) {
                                          throwIfInterrupted(job.interrupter);
                                          cpu::WordMarker row_marker(grid, offset);
                                          rasterizeRowsAnyAxis(t, r.begin(), r.end(), row_marker);
                                      });
                }
                done.fetch_add(chunk.size(), std::memory_order_relaxed);
            });
    });
    stats.addTiming("voxelize", watch.elapsedMs());
    if (!stats.cpu) stats.cpu.emplace();
    stats.cpu->split_triangles += split_triangles.load();
}

}  // namespace hyvox
