// SPDX-License-Identifier: GPL-3.0-or-later
// The 'cpu' method: every triangle's factored test, in parallel over chunks of triangles
// with TBB. Bits are set with relaxed atomic ORs on whole words (no locks). A triangle
// covering many columns of its dominant plane is split by rows into tasks of its own, so
// one big wall cannot leave a core idle. Small triangles take shortcuts that decide the
// same voxels (vertex_cells.h, triangle_setup.h, rasterize_small.h; why: docs/why/cpu-voxelize.md).
#include <algorithm>
#include <array>
#include <atomic>
#include <memory>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "core/avx2_clones.h"
#include "core/backends.h"
#include "core/stopwatch.h"
#include "cpu/mark_voxels.h"
#include "cpu/rasterize_planeless.h"
#include "cpu/rasterize_small.h"
#include "cpu/rasterize_triangle.h"
#include "cpu/triangle_setup.h"
#include "cpu/vertex_cells.h"
#include "hyvox/zero_page_allocator.h"

namespace hyvox {
namespace {

// Columns of the dominant plane above which a triangle's rows become separate tasks.
constexpr long kSplitColumns = 64 * 64;
constexpr int kRowsPerTask = 8;
constexpr std::size_t kTrianglesPerChunk = 4096;
constexpr std::size_t kPrefetchAhead = 8;

// Every vertex's cells (vertex_cells.h) and voxel-space position, computed once each in
// parallel, or none when the tile's triangles are too few for that to pay (a closed mesh has
// about two triangles per vertex; a tile of a large grid holds a few of the mesh's triangles).
// The positions are the very values spec.toVoxel gives per corner (three divisions each, and
// most triangles would repeat them for vertices their neighbours share).
struct VertexCache {
    std::unique_ptr<cpu::VertexCell[]> cells;
    std::unique_ptr<std::array<double, 3>[]> voxel;
    explicit operator bool() const { return bool(cells); }
};

VertexCache vertexCache(const ValidatedMesh& mesh, const GridSpec& spec) {
    const std::size_t n = mesh.view.vertex_count;
    VertexCache cache;
    if (2 * n > 3 * mesh.usable.size()) return cache;
    cache.cells.reset(new cpu::VertexCell[n]);
    cache.voxel.reset(new std::array<double, 3>[n]);
    adviseHugePages(cache.cells.get(), n * sizeof(cache.cells[0]));
    adviseHugePages(cache.voxel.get(), n * sizeof(cache.voxel[0]));
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1 << 14), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t v = r.begin(); v != r.end(); ++v) {
            const float* p = mesh.view.positions + 3 * v;
            cache.voxel[v] = spec.toVoxel(std::array<float, 3>{p[0], p[1], p[2]});
            cache.cells[v] = cpu::vertexCell(cache.voxel[v]);
        }
    });
    return cache;
}

// At most 3 candidates along each axis: those are checked against the voxels already set
// before any setup; a larger triangle rarely finds all of its candidates set.
bool fewCandidates(const cpu::CandidateRange& r) {
    return r.hi[0] - r.lo[0] <= 2 && r.hi[1] - r.lo[1] <= 2 && r.hi[2] - r.lo[2] <= 2;
}

void rasterizeRowsAnyAxis(const cpu::TriangleSetup& t, int row_begin, int row_end, cpu::WordMarker& marker) {
    switch (t.w) {
        case 0: cpu::rasterizeRows<0>(t, row_begin, row_end, marker); break;
        case 1: cpu::rasterizeRows<1>(t, row_begin, row_end, marker); break;
        default: cpu::rasterizeRows<2>(t, row_begin, row_end, marker); break;
    }
}

// What every chunk of one tile's triangles shares.
struct TileWork {
    const BackendJob& job;
    const ValidatedMesh& mesh;
    const GridSpec& spec;
    BitGrid& grid;
    std::array<std::int32_t, 3> offset, last;
    Mode mode;
    const cpu::VertexCell* cells;  // null: no vertex cache (see vertexCache)
    const std::array<double, 3>* voxel;
    std::atomic<std::size_t>& done;
    std::atomic<std::uint64_t>& split_triangles;
    std::atomic<std::uint64_t>& already_covered;
};

// The triangles usable[begin, end) of one tile; an AVX2 copy where the platform dispatches by
// processor (core/avx2_clones.h).
HYVOX_AVX2_CLONES_GCC
void voxelizeChunk(const TileWork& work, std::size_t begin, std::size_t end) {
    const BackendJob& job = work.job;
    const ValidatedMesh& mesh = work.mesh;
    const auto& usable = mesh.usable;
    const GridSpec& spec = work.spec;
    BitGrid& grid = work.grid;
    const std::array<std::int32_t, 3>& offset = work.offset;
    const std::array<std::int32_t, 3>& last = work.last;
    const Mode mode = work.mode;
    const cpu::VertexCell* cells = work.cells;
    const std::array<double, 3>* voxel = work.voxel;
    std::atomic<std::size_t>& done = work.done;
    std::atomic<std::uint64_t>& split_triangles = work.split_triangles;
    std::atomic<std::uint64_t>& already_covered = work.already_covered;
    throwIfInterrupted(job.interrupter,
                       int(100 * done.load(std::memory_order_relaxed) / std::max<std::size_t>(usable.size(), 1)));
    cpu::WordMarker marker(grid, offset);
    auto corners = [&](std::uint32_t triangle) {
        return std::array<std::array<double, 3>, 3>{spec.toVoxel(mesh.vertex(triangle, 0)),
                                                    spec.toVoxel(mesh.vertex(triangle, 1)),
                                                    spec.toVoxel(mesh.vertex(triangle, 2))};
    };
    auto markAll = [&](const std::array<int, 3>& lo, const std::array<int, 3>& hi) {
        for (int i = lo[0]; i <= hi[0]; ++i)
            for (int j = lo[1]; j <= hi[1]; ++j)
                for (int k = lo[2]; k <= hi[2]; ++k) marker.mark(i, j, k);
    };
    // The factored test of one triangle whose candidate range is not outside.
    auto rasterize = [&](const std::array<double, 3>& c0, const std::array<double, 3>& c1,
                         const std::array<double, 3>& c2, const cpu::CandidateRange& range) {
        cpu::TriangleSetup t;
        const cpu::SetupKind kind = cpu::setupTriangle(c0, c1, c2, mode, range, t);
        if (kind == cpu::SetupKind::Outside) return;
        if (kind == cpu::SetupKind::AllCandidates) {
            markAll(t.lo, t.hi);
            return;
        }
        if (kind == cpu::SetupKind::Planeless) {
            cpu::rasterizePlaneless({c0, c1, c2}, mode, t.lo, t.hi, marker);
            return;
        }
        if (cpu::fitsSmallPath(t)) {
            cpu::rasterizeSmall(t, marker);
            return;
        }
        const int rows = t.hi[1] - t.lo[1] + 1;
        const long columns = long(rows) * (t.hi[0] - t.lo[0] + 1);
        if (columns <= kSplitColumns) {
            rasterizeRowsAnyAxis(t, t.lo[1], t.hi[1] + 1, marker);
            return;
        }
        split_triangles.fetch_add(1, std::memory_order_relaxed);
        tbb::parallel_for(tbb::blocked_range<int>(t.lo[1], t.hi[1] + 1, kRowsPerTask),
                          [&](const tbb::blocked_range<int>& r) {
                              throwIfInterrupted(job.interrupter);
                              cpu::WordMarker row_marker(grid, offset);
                              rasterizeRowsAnyAxis(t, r.begin(), r.end(), row_marker);
                          });
    };
    // This chunk's triangles checked against the voxels set, and skipped, per kind
    // (within one voxel's range along one axis, or none). Where few of a kind are
    // skipped (coarser triangles, whose voxels their neighbours rarely cover) its
    // check stops for the rest of the chunk (docs/why/cpu-voxelize.md).
    std::uint64_t checked[2] = {0, 0}, skipped[2] = {0, 0};
    auto coveredAlready = [&](const cpu::CandidateRange& range) {
        const int kind = range.singleAxes() == 0 ? 0 : 1;
        if (!fewCandidates(range) || (checked[kind] >= 64 && 16 * skipped[kind] < checked[kind])) return false;
        ++checked[kind];
        if (!marker.allMarked(range.lo, range.hi)) return false;
        ++skipped[kind];
        return true;
    };
    if (!cells) {
        for (std::size_t n = begin; n != end; ++n) {
            const auto voxel_corners = corners(usable[n]);
            const cpu::CandidateRange range = cpu::candidateRange(voxel_corners, offset, last);
            if (range.outside()) continue;
            // Every candidate set already: nothing to add (mark_voxels.h).
            if (coveredAlready(range)) continue;
            rasterize(voxel_corners[0], voxel_corners[1], voxel_corners[2], range);
        }
        already_covered.fetch_add(skipped[0] + skipped[1], std::memory_order_relaxed);
        done.fetch_add((end - begin), std::memory_order_relaxed);
        return;
    }
    auto cellRangeOf = [&](std::size_t n) {
        const std::uint32_t* idx = mesh.view.triangles + 3 * std::size_t(usable[n]);
        return cpu::cellRange(cells[idx[0]], cells[idx[1]], cells[idx[2]], offset, last);
    };
    // Two passes over each block of the chunk: the triangles decided from integers
    // alone mark their voxels first, then the widest of the rest (within one
    // voxel's range along no axis), then the others, so that more of them find all
    // of their candidates set when their turn comes (docs/why/cpu-voxelize.md).
    std::uint16_t deferred[kTrianglesPerChunk];
    for (std::size_t block = begin; block < end; block += kTrianglesPerChunk) {
        const std::size_t block_end = std::min(end, block + kTrianglesPerChunk);
        std::size_t deferred_count = 0, later_begin = block_end - block;
        for (std::size_t n = block; n != block_end; ++n) {
            // The integer first look finds the candidate range setupTriangle would.
            // Its loads are the loop's cost (vertices are spread over megabytes):
            // those of a triangle a few ahead are requested now.
            if (n + kPrefetchAhead < block_end) {
                const std::uint32_t* ahead = mesh.view.triangles + 3 * std::size_t(usable[n + kPrefetchAhead]);
                for (int c = 0; c < 3; ++c) __builtin_prefetch(&cells[ahead[c]]);
            }
            const cpu::CandidateRange range = cellRangeOf(n);
            if (range.outside()) continue;
            if (mode != Mode::Thin && range.singleAxes() >= 2)
                markAll(range.lo, range.hi);
            else if (range.singleAxes() == 0)
                deferred[deferred_count++] = std::uint16_t(n - block);
            else
                deferred[--later_begin] = std::uint16_t(n - block);
        }
        std::reverse(deferred + later_begin, deferred + (block_end - block));
        std::copy(deferred + later_begin, deferred + (block_end - block), deferred + deferred_count);
        deferred_count += block_end - block - later_begin;
        for (std::size_t d = 0; d != deferred_count; ++d) {
            // Their corners' coordinates are not cached yet: requested a few ahead.
            if (d + kPrefetchAhead < deferred_count) {
                const std::uint32_t* ahead =
                    mesh.view.triangles + 3 * std::size_t(usable[block + deferred[d + kPrefetchAhead]]);
                for (int c = 0; c < 3; ++c) __builtin_prefetch(&voxel[ahead[c]]);
            }
            const std::size_t n = block + deferred[d];
            const cpu::CandidateRange range = cellRangeOf(n);
            // Every candidate set already: nothing to add (mark_voxels.h).
            if (coveredAlready(range)) continue;
            const std::uint32_t* idx = mesh.view.triangles + 3 * std::size_t(usable[n]);
            rasterize(voxel[idx[0]], voxel[idx[1]], voxel[idx[2]], range);
        }
    }
    already_covered.fetch_add(skipped[0] + skipped[1], std::memory_order_relaxed);
    done.fetch_add((end - begin), std::memory_order_relaxed);
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
    std::atomic<std::uint64_t> already_covered{0};

    const int threads = job.options.threads > 0 ? job.options.threads : tbb::task_arena::automatic;
    tbb::task_arena arena(threads);
    arena.execute([&] {
        const VertexCache cache = vertexCache(mesh, spec);
        const TileWork work{job,
                            mesh,
                            spec,
                            grid,
                            offset,
                            last,
                            mode,
                            cache.cells.get(),
                            cache.voxel.get(),
                            done,
                            split_triangles,
                            already_covered};
        tbb::parallel_for(
            tbb::blocked_range<std::size_t>(0, usable.size(), kTrianglesPerChunk),
            [&](const tbb::blocked_range<std::size_t>& chunk) { voxelizeChunk(work, chunk.begin(), chunk.end()); });
    });
    stats.addTiming("voxelize", watch.elapsedMs());
    if (!stats.cpu) stats.cpu.emplace();
    stats.cpu->split_triangles += split_triangles.load();
    stats.cpu->triangles_already_covered += already_covered.load();
}

}  // namespace hyvox
