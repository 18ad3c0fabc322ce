// SPDX-License-Identifier: GPL-3.0-or-later
// runGlBackend: methods `triangle`, `fragment` and `hybrid` (JCGT 2013 sections 3.2-3.4).
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>

#include "core/backends.h"
#include "core/stopwatch.h"
#include "gl/gl_worker.h"
#include "gl/shader_library.h"
#include "hybrid/cutoff_search.h"
#include "hybrid/gl_backend_internal.h"
#include "hybrid/gl_voxelizer.h"
#include "hybrid/gpu_mesh.h"
#include "hyvox/errors.h"

namespace hyvox {
namespace hybrid {
namespace {

// The largest projected area on a dominant plane, in voxel units² (the search's upper end).
double largestProjectedArea(const GpuMesh& mesh) {
    double largest = 0;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
        largest = std::max(largest, projectedArea(triangleCorners(mesh, t)));
    return largest;
}

std::string cacheKey(const GpuMesh& mesh, const GridSpec& grid, Mode mode, const gl::GlWorker& worker) {
    return std::to_string(mesh.fingerprint) + "/" + std::to_string(grid.dims[0]) + "x" + std::to_string(grid.dims[1]) +
           "x" + std::to_string(grid.dims[2]) + "/" + toString(mode) + "/" + worker.renderer();
}

}  // namespace

GlRun runGl(const BackendJob& job, BitGrid* out, std::vector<std::array<std::int32_t, 3>>* voxel_list) {
    const Method method = job.options.method;
    if (method != Method::Triangle && method != Method::Fragment && method != Method::Hybrid)
        throw BackendError(std::string("the GL backend does not run method '") + toString(method) + "'");
    GlRun run;
    Stopwatch watch;
    const GpuMesh mesh = makeGpuMesh(job.mesh, job.grid);
    run.prepare_ms = watch.restart();
    gl::GlWorker& worker = gl::GlWorker::get(job.options.gl.device);
    const std::string shader_dir = gl::resolveShaderDir(job.options.gl.shader_dir);

    worker.run([&] {
        Stopwatch gl_watch;
        const GlTuning tuning = GlTuning::forDevice(worker.device().software);
        GlVoxelizer voxelizer(mesh, job.grid, job.options.mode, method, shader_dir, worker.programs(), tuning);
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
        } else {
            run.times = voxelizer.run(cutoff, out, [&] { throwIfInterrupted(job.interrupter); });
        }
        run.voxelize_ms = gl_watch.restart() - run.times.readback_ms;
    });
    return run;
}

}  // namespace hybrid

void runGlBackend(const BackendJob& job, VoxelizeResult& result) {
    const hybrid::GlRun run = hybrid::runGl(job, &result.occupancy, nullptr);
    Stats& stats = result.stats;
    stats.addTiming("gl_prepare", run.prepare_ms);
    stats.addTiming("gl_upload", run.upload_ms);
    if (run.search_runs)
        stats.addTiming("gl_cutoff_search", run.search_ms);
    stats.addTiming("gl_voxelize", run.voxelize_ms);
    stats.addTiming("gl_readback", run.times.readback_ms);
    stats.metrics["upload_ms"] = run.upload_ms;
    stats.metrics["readback_ms"] = run.times.readback_ms;
    stats.metrics["pass1_gpu_ms"] = run.times.pass1_gpu_ms;
    stats.metrics["pass2_gpu_ms"] = run.times.pass2_gpu_ms;
    stats.metrics["gpu_ms"] = run.times.pass1_gpu_ms + run.times.pass2_gpu_ms;
    stats.metrics["tiles"] = run.times.tiles;
    if (job.options.method == Method::Hybrid) {
        stats.metrics["cutoff"] = run.cutoff;
        stats.metrics["large_triangles"] = double(run.times.large_triangles);
        stats.metrics["cutoff_search_runs"] = run.search_runs;
    }
}

}  // namespace hyvox
