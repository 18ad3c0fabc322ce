// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The GL passes of the `triangle`, `fragment` and `hybrid` methods over one uploaded mesh.
// Construct and use only inside gl::GlWorker::run (it owns GL objects).
//
// Grids whose bit volume exceeds one shader storage block (GL_MAX_SHADER_STORAGE_BLOCK_SIZE,
// or the HYVOX_GL_TILE_BYTES override used by tests) run in tiles: slabs of whole 8³ bricks
// along x, which are contiguous in the OpenVDB leaf layout and read back straight into
// place. Limits are checked before anything big is allocated.
#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "gl/gl_objects.h"
#include "gl/shader_library.h"
#include "hybrid/gpu_mesh.h"
#include "hyvox/bit_grid.h"
#include "hyvox/grid.h"
#include "hyvox/options.h"

namespace hyvox::hybrid {

struct PassTimes {
    double pass1_gpu_ms = 0;            // compute: triangle-parallel, or hybrid classify + small triangles
    double pass2_gpu_ms = 0;            // rasterization: fragment-parallel, or hybrid's large triangles
    std::uint64_t large_triangles = 0;  // hybrid: triangles deferred to pass 2 (summed over tiles)
    double readback_ms = 0;
    int tiles = 0;
};

// Device quirks; GlTuning::forDevice picks them.
struct GlTuning {
    // Time passes by the CPU clock around glFinish instead of GL_TIME_ELAPSED queries: for
    // Mesa's llvmpipe, whose timer queries miss compute dispatches (they read ~0) and are
    // erratic for draws; its "GPU" is the CPU, so the wall clock measures the same work.
    bool wall_timing = false;
    // Columns per side of one compute invocation's share of a triangle (0 = the whole
    // triangle): llvmpipe stops any invocation after 65535 loop iterations in total, so it
    // needs chunks (see shaders/common/voxelize_triangle.glsl).
    int chunk_side = 0;
    static GlTuning forDevice(bool software);  // env HYVOX_GL_WALL_TIMING=1 forces wall timing
};

class GlVoxelizer {
public:
    GlVoxelizer(const GpuMesh& mesh, const GridSpec& grid, Mode mode, Method method, const std::string& shader_dir,
                gl::ProgramCache& programs, const GlTuning& tuning);

    // Runs every tile; writes bits into `out` (dims = grid dims) unless it is null (timing
    // runs). before_tile (optional) runs before each tile: a place to throw Cancelled.
    PassTimes run(double cutoff, BitGrid* out, const std::function<void()>& before_tile = {});

    // Section 3.5: the set voxels as a list (x, y, z), each once, in no particular order.
    std::vector<std::array<std::int32_t, 3>> runVoxelList(double cutoff, PassTimes* times = nullptr);

    int tileCount() const { return int(tiles_.size()); }

private:
    struct Tile {
        int brick_x0, brick_x1;  // [x0, x1) in bricks
    };
    // A program and its active uniform locations (bit i: location i), found once: only
    // active uniforms may be set (a location the compiler dropped is an error in GL).
    struct Stage {
        const gl::Program* program = nullptr;
        std::uint32_t active = 0;
    };
    struct Programs {
        Stage triangle, classify, raster;
        bool built = false;
    };
    // Built on first use, then kept for this voxelizer's runs ([voxel_list]).
    const Programs& programsFor(bool voxel_list);
    void runTile(const Tile& tile, const Programs& programs, double cutoff, PassTimes& times);
    // Calls set(program id) for each of the programs that uses uniform `location`.
    template <typename Set>
    void setUniform(const Programs& programs, GLint location, const Set& set) const;
    void setRunUniforms(const Programs& programs, double cutoff) const;  // the same for every tile
    void setTileUniforms(const Programs& programs, const Tile& tile) const;

    const GridSpec& grid_;
    Mode mode_;
    Method method_;
    std::string shader_dir_;
    gl::ProgramCache& programs_;
    std::uint32_t triangle_count_;
    std::array<std::int32_t, 3> bricks_;
    std::vector<Tile> tiles_;
    Programs programs_by_list_[2];
    gl::Buffer vertices_, triangles_, bits_, large_, draw_, voxel_list_;
    gl::VertexArray empty_vao_;
    gl::Framebuffer framebuffer_;
    GlTuning tuning_;
    // llvmpipe only: per-triangle bounding-box side and projected area, for chunksFor().
    std::vector<float> extents_, areas_;
    // Compute work groups along z: chunks of the largest triangle pass 1 voxelizes.
    std::uint32_t chunksFor(double cutoff) const;
};

}  // namespace hyvox::hybrid
