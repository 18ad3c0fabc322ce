// SPDX-License-Identifier: GPL-3.0-or-later
// The `tessellation` method (point-tessellated voxelization): plan the patches on the CPU,
// tessellate and inject points on the GPU, then turn the per-brick count blocks into
// VoxelizeResult::counts. Its accuracy against an exact method is measured by the caller
// (hyvox/accuracy.h), never here: a backend does not run another.
#include <algorithm>
#include <cmath>
#include <optional>

#include "core/backends.h"
#include "core/stopwatch.h"
#include "gl/gpu_mesh.h"
#include "hyvox/errors.h"
#include "tessellation/displacement_map.h"
#include "tessellation/gl_tessellation.h"
#include "tessellation/patch_plan.h"
#include "tessellation/point_values.h"
#include "tessellation/surface_attributes.h"

namespace hyvox {
namespace {

// What the options schema cannot check: the image is sampled at the mesh's UVs.
void checkDisplacementInput(const ValidatedMesh& mesh, bool displaced) {
    if (displaced && !mesh.view.uvs)
        throw InvalidInput("displacement needs per-vertex UVs (the image is sampled at the interpolated UV)");
}

// Block b of the pool holds brick `brick`'s 512 counts in OpenVDB leaf order; voxels are
// given in grid coordinates (the tile's plus its offset).
void compactCounts(const std::vector<std::uint32_t>& brick_blocks, const std::vector<std::uint32_t>& pool,
                   const BitGrid& grid, const std::array<std::int32_t, 3>& offset, std::vector<VoxelCount>& counts) {
    const BrickLayout& bricks = grid.bricks();
    for (std::size_t brick = 0; brick < bricks.total(); ++brick) {
        const std::uint32_t block = brick_blocks[brick];
        if (block == 0 || std::size_t(block) * 512 > pool.size()) continue;
        const std::array<std::int32_t, 3> b = bricks.at(brick);
        const std::uint32_t* c = pool.data() + std::size_t(block - 1) * 512;
        for (int n = 0; n < 512; ++n)
            if (c[n])
                counts.push_back({offset[0] + b[0] * 8 + (n >> 6), offset[1] + b[1] * 8 + ((n >> 3) & 7),
                                  offset[2] + b[2] * 8 + (n & 7), c[n]});
    }
}

}  // namespace

void runTessellationBackend(const BackendJob& job, TileOutput& result, Stats& stats) {
    const TessellationOptions& options = job.options.tessellation;
    Stopwatch watch;
    const tessellation::DisplacementMap map = tessellation::DisplacementMap::fromOptions(options);
    checkDisplacementInput(job.mesh, !map.empty());
    // Normals and UVs only matter to PN-triangles and displacement; flat runs skip them.
    const bool curved = options.pn_triangles || !map.empty();
    // The dispatcher bins each triangle by its box grown by how far its points may move
    // (tiling::pointReach), so every point is drawn in the tile it lands in.
    std::optional<tessellation::SurfaceAttributes> surface;
    if (curved) surface.emplace(job.whole_mesh, job.grid);
    const std::vector<float> none;
    const gl::GpuMesh gpu_mesh = gl::makeGpuMesh(job.mesh, job.grid, job.tile.offset);
    const int max_level = tessellation::maxTessellationLevel(job.options.gl.device);
    // How far points may leave the flat triangles: the displacement's largest offset, and
    // for PN-triangles a share of each triangle's size (a cubic patch bulges well under half).
    const double displacement_reach = map.empty() ? 0.0
                                                  : std::max(std::abs(map.maxValue() - options.displacement_midlevel),
                                                             std::abs(map.minValue() - options.displacement_midlevel)) *
            std::abs(options.displacement_strength) / job.grid.voxel_size;
    // Attribute means divide per-voxel sums by the per-voxel counts, so they need the counts.
    std::optional<tessellation::PointValues> values;
    if (job.attributes) values.emplace(tessellation::makePointValues(job.mesh, job.grid, *job.attributes));
    const bool counts = options.counts || values;
    const tessellation::PatchPlan plan =
        tessellation::planPatches(job.mesh, job.grid, job.tile.offset, job.tile.dims, options.gamma, max_level, counts,
                                  displacement_reach + 1.0, options.pn_triangles ? 0.5 : 0.0);
    stats.addTiming("plan", watch.restart());
    throwIfInterrupted(job.interrupter, 10);

    const tessellation::GpuTessellationInput input{
        gpu_mesh,
        curved ? surface->normals() : none,
        curved ? surface->uvs() : none,
        plan,
        max_level,
        job.tile.dims,
        options.gamma,
        options.pn_triangles,
        map.empty() ? none : map.bottomUpRows(),
        map.width(),
        map.height(),
        options.displacement_strength / job.grid.voxel_size,
        options.displacement_midlevel,
        counts,
        values ? &*values : nullptr,
        job.options.memoryBudgetBytes(),
        job.options.gl,
        job.interrupter,
    };
    const tessellation::GpuTessellationOutput out = tessellation::runGpuTessellation(input, result.bits);
    stats.addTiming("tessellate", watch.restart());

    if (options.counts) {
        compactCounts(out.brick_blocks, out.count_pool, result.bits, job.tile.offset, result.counts);
        stats.addTiming("counts", watch.restart());
    }
    if (values) {
        result.attribute_voxels_unreached +=
            tessellation::meansFromSums(out.brick_blocks, out.count_pool, out.value_pool, result.bits, job.tile.offset,
                                        job.grid, values->layout, result.attributes);
        stats.addTiming("attributes", watch.restart());
    }
    // Summed over tiles: a triangle reaching k tiles is drawn k times, and its points outside
    // a tile count as clipped there, so points - points_clipped are the points that landed.
    TessellationStats& figures = stats.tessellation ? *stats.tessellation : stats.tessellation.emplace();
    figures.gamma = options.gamma;
    figures.points += out.points;
    figures.points_clipped += out.clipped;
    figures.triangles_whole += plan.whole.size();
    figures.patches_direct += plan.direct.size();
    figures.patches_split += plan.split_patches;
    figures.split_triangles += plan.splits.size() / 4;
    figures.largest_split = std::max<std::uint64_t>(figures.largest_split, plan.largest_split);
    figures.max_tess_level = std::uint64_t(max_level);
    figures.pass0_gpu_ms += out.whole_gpu_ms;
    figures.pass1_gpu_ms += out.direct_gpu_ms;
    figures.pass2_gpu_ms += out.split_gpu_ms;
    figures.gpu_runs += std::uint64_t(out.runs);
}

}  // namespace hyvox
