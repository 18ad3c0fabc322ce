// SPDX-License-Identifier: GPL-3.0-or-later
// runHybridBackend: methods `triangle`, `fragment` and `hybrid` (JCGT 2013 sections 3.2-3.4;
// triangle and fragment are the hybrid's two limits).
#include <algorithm>
#include <cmath>
#include <string>

#include "core/backends.h"
#include "core/stopwatch.h"
#include "gl/gl_tuning.h"
#include "gl/gl_worker.h"
#include "gl/gpu_mesh.h"
#include "hybrid/cutoff_search.h"
#include "hybrid/gl_voxelizer.h"
#include "hybrid/hybrid_run.h"
#include "hyvox/errors.h"

namespace hyvox {
namespace hybrid {
namespace {

// The largest projected area on a dominant plane, in voxel units² (the search's upper end).
double largestProjectedArea(const gl::GpuMesh& mesh) {
    double largest = 0;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
        largest = std::max(largest, gl::projectedArea(gl::triangleCorners(mesh, t)));
    return largest;
}

std::string cacheKey(const gl::GpuMesh& mesh, const GridSpec& grid, Mode mode, const gl::GlWorker& worker) {
    return std::to_string(mesh.fingerprint) + "/" + grid.dimsText() + "/" + toString(mode) + "/" + worker.renderer();
}

}  // namespace

HybridRun runHybrid(const BackendJob& job, BitGrid* out, std::vector<std::array<std::int32_t, 3>>* voxel_list,
                    std::vector<VoxelPiece>* pieces) {
    const Method method = job.options.method;
    if (method != Method::Triangle && method != Method::Fragment && method != Method::Hybrid)
        throw BackendError(std::string("the hybrid backend does not run method '") + toString(method) + "'");
    HybridRun run;
    Stopwatch watch;
    const gl::GpuMesh mesh = gl::makeGpuMesh(job.mesh, job.grid, job.tile.offset);
    // The GL passes see the tile as their grid (cells are relative to its first voxel).
    GridSpec tile_grid = job.grid;
    tile_grid.dims = job.tile.dims;
    run.prepare_ms = watch.restart();
    const GlOptions& gl_options = job.options.gl;
    gl::GlWorker& worker = gl::GlWorker::get(gl_options.device);

    worker.run([&] {
        Stopwatch gl_watch;
        const gl::GlTuning tuning = gl::GlTuning::forDevice(worker.device().software, gl_options);
        GlVoxelizer voxelizer(mesh, tile_grid, job.options.mode, method, gl_options.shader_dir, worker.programs(),
                              tuning, gl_options.tile_bytes, gl_options.pair_list_bytes);
        glFinish();
        run.upload_ms = gl_watch.restart();
        throwIfInterrupted(job.interrupter);

        double cutoff = job.options.hybrid.cutoff;
        if (method == Method::Hybrid && cutoff < 0) {
            const CutoffSearch search = cachedCutoff(cacheKey(mesh, job.grid, job.options.mode, worker), [&] {
                return searchCutoff(
                    [&](double c) {
                        throwIfInterrupted(job.interrupter);
                        const PassTimes t = voxelizer.run(c, nullptr);
                        return t.pass1_gpu_ms + t.pass2_gpu_ms;
                    },
                    largestProjectedArea(mesh));
            });
            cutoff = search.cutoff;
            run.search_runs = search.evaluations;
            run.search_ms = gl_watch.restart();
        }
        run.cutoff = method == Method::Hybrid ? cutoff : (method == Method::Triangle ? INFINITY : 0.0);
        if (voxel_list) {
            *voxel_list = voxelizer.runVoxelList(cutoff, &run.times);
        } else if (pieces && job.options.mode == Mode::Thin) {
            // A voxel's value sums every triangle whose closed box meets it, and the thin test
            // leaves some of those out: the pairs come from a conservative pass of their own,
            // whose extra voxels the dispatcher skips (only set voxels get values).
            run.times = voxelizer.run(cutoff, out, [&] { throwIfInterrupted(job.interrupter); });
            GlVoxelizer conservative(mesh, tile_grid, Mode::Conservative, method, gl_options.shader_dir,
                                     worker.programs(), tuning, gl_options.tile_bytes, gl_options.pair_list_bytes);
            const PassTimes pairs =
                conservative.runPieces(cutoff, nullptr, *pieces, [&] { throwIfInterrupted(job.interrupter); });
            run.times.pass1_gpu_ms += pairs.pass1_gpu_ms;
            run.times.pass2_gpu_ms += pairs.pass2_gpu_ms;
            run.times.clip_gpu_ms += pairs.clip_gpu_ms;
        } else if (pieces) {
            run.times = voxelizer.runPieces(cutoff, out, *pieces, [&] { throwIfInterrupted(job.interrupter); });
        } else {
            run.times = voxelizer.run(cutoff, out, [&] { throwIfInterrupted(job.interrupter); });
        }
        run.voxelize_ms = gl_watch.restart() - run.times.readback_ms - run.times.clip_gpu_ms;
    });
    return run;
}

}  // namespace hybrid

void runHybridBackend(const BackendJob& job, TileOutput& out, Stats& stats) {
    const hybrid::HybridRun run = hybrid::runHybrid(job, &out.bits, nullptr, job.clip_pieces ? &out.pieces : nullptr);
    stats.addTiming("gl_prepare", run.prepare_ms);
    stats.addTiming("gl_upload", run.upload_ms);
    if (run.search_runs) stats.addTiming("gl_cutoff_search", run.search_ms);
    stats.addTiming("gl_voxelize", run.voxelize_ms);
    stats.addTiming("gl_readback", run.times.readback_ms);
    if (job.clip_pieces) stats.addTiming("gl_clip_pieces", run.times.clip_gpu_ms);
    // Summed over the dispatcher's tiles. The automatic cutoff is cached per whole mesh and
    // grid, so the first tile searches it and the others reuse it.
    HybridStats& figures = stats.hybrid ? *stats.hybrid : stats.hybrid.emplace();
    figures.pass1_gpu_ms += run.times.pass1_gpu_ms;
    figures.pass2_gpu_ms += run.times.pass2_gpu_ms;
    figures.upload_ms += run.upload_ms;
    figures.readback_ms += run.times.readback_ms;
    figures.tiles += std::uint64_t(run.times.tiles);
    figures.cutoff = run.cutoff;
    figures.large_triangles += run.times.large_triangles;
    figures.cutoff_search_runs += std::uint64_t(run.search_runs);
}

}  // namespace hyvox
