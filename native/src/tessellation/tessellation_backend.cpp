// SPDX-License-Identifier: GPL-3.0-or-later
// The `tessellation` method (point-tessellated voxelization): plan the patches on the CPU,
// tessellate and inject points on the GPU, then turn the per-brick count blocks into
// VoxelizeResult::counts and, when asked, measure the result against the exact cpu method.
#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include "core/backends.h"
#include "core/stopwatch.h"
#include "gl/shader_library.h"
#include "hybrid/gpu_mesh.h"
#include "hyvox/accuracy.h"
#include "hyvox/errors.h"
#include "tessellation/displacement_map.h"
#include "tessellation/gl_tessellation.h"
#include "tessellation/patch_plan.h"
#include "tessellation/surface.h"

namespace hyvox {
namespace {

void checkOptions(const TessellationOptions& o, const ValidatedMesh& mesh, bool displaced) {
    if (!std::isfinite(o.gamma) || o.gamma <= 0.0 || o.gamma > 1024.0)
        throw InvalidInput("tessellation gamma must be in (0, 1024], got " + std::to_string(o.gamma));
    if (!std::isfinite(o.displacement_strength) || !std::isfinite(o.displacement_midlevel))
        throw InvalidInput("displacement strength and midlevel must be finite numbers");
    if (displaced && !mesh.view.uvs)
        throw InvalidInput("displacement needs per-vertex UVs (the image is sampled at the interpolated UV)");
}

// Block b of the pool holds brick `brick`'s 512 counts in OpenVDB leaf order.
std::vector<VoxelCount> compactCounts(const std::vector<std::uint32_t>& brick_blocks,
                                      const std::vector<std::uint32_t>& pool, const BitGrid& grid) {
    std::vector<VoxelCount> counts;
    const auto& bricks = grid.bricks();
    for (std::int32_t bx = 0; bx < bricks[0]; ++bx)
        for (std::int32_t by = 0; by < bricks[1]; ++by)
            for (std::int32_t bz = 0; bz < bricks[2]; ++bz) {
                const std::size_t brick = (std::size_t(bx) * bricks[1] + by) * bricks[2] + bz;
                const std::uint32_t block = brick_blocks[brick];
                if (block == 0 || std::size_t(block) * 512 > pool.size()) continue;
                const std::uint32_t* c = pool.data() + std::size_t(block - 1) * 512;
                for (int n = 0; n < 512; ++n)
                    if (c[n]) counts.push_back({bx * 8 + (n >> 6), by * 8 + ((n >> 3) & 7), bz * 8 + (n & 7), c[n]});
            }
    return counts;
}

void measureAccuracy(const BackendJob& job, VoxelizeResult& result) {
    VoxelizeOptions exact = job.options;
    exact.method = Method::Cpu;
    auto exactVoxels = [&](Mode mode) {
        exact.mode = mode;
        VoxelizeResult reference;
        reference.grid = job.grid;
        reference.occupancy = BitGrid(job.grid.dims);
        runCpuBackend(BackendJob{job.mesh, job.grid, exact, job.interrupter}, reference);
        return std::move(reference.occupancy);
    };
    const BitGrid conservative = exactVoxels(Mode::Conservative);
    const AccuracyReport accuracy = compareToReference(result.occupancy, conservative);
    const WatertightReport rays = rayMarchWatertightness(result.occupancy, conservative, job.mesh, job.grid);
    // The share of the thin (6-separating) voxels missed: the points sit between the thin
    // and the conservative set, and this is the figure closest to the paper's bias.
    const double thin_bias = compareToReference(result.occupancy, exactVoxels(Mode::Thin)).bias;
    auto& m = result.stats.metrics;
    m["reference_voxels"] = double(accuracy.reference_voxels);
    m["missed_voxels"] = double(accuracy.missed_voxels);
    m["false_voxels"] = double(accuracy.false_voxels);
    m["bias"] = accuracy.bias;
    m["bias_thin"] = thin_bias;
    m["watertight_rays"] = double(rays.rays);
    m["watertight_share"] = rays.share();
}

}  // namespace

void runTessellationBackend(const BackendJob& job, VoxelizeResult& result) {
    const TessellationOptions& options = job.options.tessellation;
    Stopwatch watch;
    const tessellation::DisplacementMap map = tessellation::DisplacementMap::fromOptions(options);
    checkOptions(options, job.mesh, !map.empty());
    // Normals and UVs only matter to PN-triangles and displacement; flat runs skip them.
    const bool curved = options.pn_triangles || !map.empty();
    std::optional<tessellation::Surface> surface;
    if (curved) surface.emplace(job.mesh, job.grid);
    const std::vector<float> none;
    const hybrid::GpuMesh gpu_mesh = hybrid::makeGpuMesh(job.mesh, job.grid);
    const int max_level = tessellation::maxTessellationLevel(job.options.gl.device);
    // How far points may leave the flat triangles: the displacement's largest offset, and
    // for PN-triangles a share of each triangle's size (a cubic patch bulges well under half).
    const double displacement_reach =
        map.empty() ? 0.0
                    : std::max(std::abs(map.maxValue() - options.displacement_midlevel),
                               std::abs(map.minValue() - options.displacement_midlevel)) *
                          std::abs(options.displacement_strength) / job.grid.voxel_size;
    const tessellation::PatchPlan plan =
        tessellation::planPatches(job.mesh, job.grid, options.gamma, max_level, options.counts,
                                  displacement_reach + 1.0, options.pn_triangles ? 0.5 : 0.0);
    result.stats.addTiming("plan", watch.restart());
    throwIfInterrupted(job.interrupter, 10);

    const tessellation::GpuTessellationInput input{
        gpu_mesh,
        curved ? surface->normals() : none,
        curved ? surface->uvs() : none,
        plan,
        max_level,
        job.grid.dims,
        options.gamma,
        options.pn_triangles,
        map.empty() ? none : map.bottomUpRows(),
        map.width(),
        map.height(),
        options.displacement_strength / job.grid.voxel_size,
        options.displacement_midlevel,
        options.counts,
        job.options.memory_budget,
        gl::resolveShaderDir(job.options.gl.shader_dir),
        job.interrupter,
    };
    const tessellation::GpuTessellationOutput out =
        tessellation::runGpuTessellation(job.options.gl.device, input, result.occupancy);
    result.stats.addTiming("tessellate", watch.restart());

    if (options.counts) {
        result.counts = compactCounts(out.brick_blocks, out.count_pool, result.occupancy);
        result.stats.addTiming("counts", watch.restart());
    }
    auto& m = result.stats.metrics;
    m["gamma"] = options.gamma;
    m["points"] = double(out.points);
    m["points_clipped"] = double(out.clipped);
    m["triangles_whole"] = double(plan.whole.size());
    m["patches_direct"] = double(plan.direct.size());
    m["patches_split"] = double(plan.split_patches);
    m["split_triangles"] = double(plan.splits.size() / 4);
    m["largest_split"] = double(plan.largest_split);
    m["max_tess_level"] = double(max_level);
    m["pass0_gpu_ms"] = out.whole_gpu_ms;   // triangles left whole (compute)
    m["pass1_gpu_ms"] = out.direct_gpu_ms;  // tessellated triangles
    m["pass2_gpu_ms"] = out.split_gpu_ms;   // pre-split triangles
    m["gpu_runs"] = double(out.runs);
    if (options.measure_accuracy) {
        measureAccuracy(job, result);
        result.stats.addTiming("accuracy", watch.restart());
    }
}

}  // namespace hyvox
