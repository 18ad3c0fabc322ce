// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The GPU part of the tessellation method: uploads the mesh and the patch plan, injects the
// points of triangles left whole (compute), runs the tessellation draw (vertex pull → Eq. 1
// factors → surface + displacement → one point per micro-triangle), and reads back bits,
// point counters and per-voxel counts. Runs on the GL worker thread (gl::GlWorker::run).
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "gl/gpu_mesh.h"
#include "hyvox/bit_grid.h"
#include "hyvox/interrupter.h"
#include "hyvox/options.h"
#include "tessellation/patch_plan.h"
#include "tessellation/point_values.h"

namespace hyvox::tessellation {

struct GpuTessellationInput {
    const gl::GpuMesh& mesh;            // triangles = the usable ones, in usable order
    const std::vector<float>& normals;  // per vertex, unit
    const std::vector<float>& uvs;      // per vertex
    const PatchPlan& plan;
    int max_level;  // GL_MAX_TESS_GEN_LEVEL the plan was made for
    std::array<std::int32_t, 3> dims;
    double gamma;
    bool pn_triangles;
    // Displacement: empty heights = none.
    const std::vector<float>& heights;  // rows bottom-up
    int height_width, height_height;
    double strength_voxels, midlevel;
    bool counts;                        // per-voxel counts (forced on with values)
    const PointValues* values;          // attribute sums per voxel; null = none
    std::uint64_t memory_budget_bytes;  // what the count and value pools may take
    const GlOptions& gl;                // device, shader folder, timing and draw choices
    Interrupter* interrupter;
};

struct GpuTessellationOutput {
    std::uint64_t points = 0;                 // micro-triangles (points) generated
    std::uint64_t clipped = 0;                // of which outside the grid
    std::vector<std::uint32_t> brick_blocks;  // per brick: 0 or 1 + block (when counting)
    std::vector<std::uint32_t> count_pool;    // 512 counts per block
    std::vector<std::uint32_t> value_pool;    // valueWordsPerBlock() words per block (with values)
    double whole_gpu_ms = 0, direct_gpu_ms = 0, split_gpu_ms = 0;
    int runs = 0;  // 2 when the count pool had to grow
};

// GL_MAX_TESS_GEN_LEVEL of the worker's context.
int maxTessellationLevel(const std::string& device);

// Fills `bits` (already sized to dims) and returns the rest.
GpuTessellationOutput runGpuTessellation(const GpuTessellationInput& input, BitGrid& bits);

}  // namespace hyvox::tessellation
