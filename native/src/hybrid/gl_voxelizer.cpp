// SPDX-License-Identifier: GPL-3.0-or-later
#include "hybrid/gl_voxelizer.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string>

#include "core/stopwatch.h"
#include "gl/compute_dispatch.h"
#include "gl/gl_debug.h"
#include "gl/pass_timer.h"
#include "hybrid/gl_bindings.h"
#include "hyvox/errors.h"

namespace hyvox::hybrid {
namespace {

constexpr std::size_t kBrickBytes = 64;  // 512 bits

GLint64 glLimit(GLenum name) {
    GLint64 value = 0;
    glGetInteger64v(name, &value);
    return value;
}

std::string dimsText(const std::array<std::int32_t, 3>& d) {
    return std::to_string(d[0]) + "x" + std::to_string(d[1]) + "x" + std::to_string(d[2]);
}

// The largest bit-grid tile in bytes: one storage block, or less when tests ask for it.
std::uint64_t tileByteLimit() {
    std::uint64_t limit = std::uint64_t(glLimit(GL_MAX_SHADER_STORAGE_BLOCK_SIZE));
    if (const char* env = std::getenv("HYVOX_GL_TILE_BYTES"))
        if (const unsigned long long forced = std::strtoull(env, nullptr, 10))
            limit = std::min<std::uint64_t>(limit, forced);
    // 32-bit word indices in the shaders.
    return std::min<std::uint64_t>(limit, std::uint64_t(1) << 33);
}

// The locations (bit i: location i) of the program's active uniforms.
std::uint32_t activeUniforms(const gl::Program& program) {
    GLint count = 0;
    glGetProgramInterfaceiv(program.id(), GL_UNIFORM, GL_ACTIVE_RESOURCES, &count);
    const GLenum property = GL_LOCATION;
    std::uint32_t active = 0;
    for (GLint i = 0; i < count; ++i) {
        GLint location = -1;
        glGetProgramResourceiv(program.id(), GL_UNIFORM, GLuint(i), 1, &property, 1, nullptr, &location);
        if (location >= 0 && location < 32)
            active |= std::uint32_t(1) << location;
    }
    return active;
}

std::string definesFor(Mode mode, bool voxel_list, bool from_large_list) {
    return std::string("#define HYVOX_THIN ") + (mode == Mode::Thin ? "1" : "0") + "\n#define HYVOX_VOXEL_LIST " +
           (voxel_list ? "1" : "0") + "\n#define HYVOX_FROM_LARGE_LIST " + (from_large_list ? "1" : "0") + "\n";
}

// Per triangle: the largest side of its bounding box and its area projected on its dominant
// plane, in voxel units (llvmpipe's chunk count; see GlTuning::chunk_side).
void measureTriangles(const GpuMesh& mesh, std::vector<float>& extent, std::vector<float>& area) {
    extent.resize(mesh.triangleCount());
    area.resize(mesh.triangleCount());
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        const TriangleCorners p = triangleCorners(mesh, t);
        double side = 0;
        for (int a = 0; a < 3; ++a)
            side = std::max(side, std::max({p[0][a], p[1][a], p[2][a]}) - std::min({p[0][a], p[1][a], p[2][a]}));
        extent[t] = float(side);
        area[t] = float(projectedArea(p));
    }
}

}  // namespace

GlTuning GlTuning::forDevice(bool software) {
    GlTuning tuning;
    const char* forced = std::getenv("HYVOX_GL_WALL_TIMING");  // "1" forces it; unset, "" or "0" do not
    tuning.wall_timing = software || (forced != nullptr && *forced != '\0' && std::string(forced) != "0");
    // 90² columns of at most 4 loop iterations each stay well below 65535.
    tuning.chunk_side = software ? 90 : 0;
    return tuning;
}

GlVoxelizer::GlVoxelizer(const GpuMesh& mesh, const GridSpec& grid, Mode mode, Method method,
                         const std::string& shader_dir, gl::ProgramCache& programs, const GlTuning& tuning)
    : grid_(grid),
      mode_(mode),
      method_(method),
      shader_dir_(shader_dir),
      programs_(programs),
      triangle_count_(std::uint32_t(mesh.triangleCount())),
      tuning_(tuning) {
    // Draw calls count vertices (3 per triangle) in a GLsizei.
    if (mesh.triangleCount() > 0x2aaaaaaaull)
        throw ResourceError("too many triangles for the GL methods (at most 715 million)");
    for (int a = 0; a < 3; ++a)
        bricks_[a] = (grid.dims[a] + 7) / 8;

    // Limits first, before any large allocation.
    if (method != Method::Triangle) {
        const std::int32_t largest = std::max({grid.dims[0], grid.dims[1], grid.dims[2]});
        GLint viewport[2] = {0, 0};
        glGetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport);
        const GLint64 fb = std::min(glLimit(GL_MAX_FRAMEBUFFER_WIDTH), glLimit(GL_MAX_FRAMEBUFFER_HEIGHT));
        const GLint64 raster_limit = std::min<GLint64>({viewport[0], viewport[1], fb});
        if (largest > raster_limit)
            throw ResourceError("a " + dimsText(grid.dims) + " grid exceeds this GL device's " +
                                std::to_string(raster_limit) + "-pixel framebuffer limit for method '" +
                                toString(method) + "'; use method 'triangle' or a larger voxel size");
    }
    const std::uint64_t slab_bytes = std::uint64_t(bricks_[1]) * std::uint64_t(bricks_[2]) * kBrickBytes;
    const std::uint64_t tile_limit = tileByteLimit();
    if (slab_bytes > tile_limit)
        throw ResourceError("a " + dimsText(grid.dims) + " grid needs " + std::to_string(slab_bytes >> 20) +
                            " MiB per 8-voxel slab, more than this GL device's storage-block limit of " +
                            std::to_string(tile_limit >> 20) + " MiB; use a larger voxel size");
    const int bricks_per_tile = int(std::min<std::uint64_t>(std::uint64_t(bricks_[0]), tile_limit / slab_bytes));
    for (int x0 = 0; x0 < bricks_[0]; x0 += bricks_per_tile)
        tiles_.push_back({x0, std::min(bricks_[0], x0 + bricks_per_tile)});

    if (tuning_.chunk_side > 0 && method != Method::Fragment) measureTriangles(mesh, extents_, areas_);

    vertices_ = gl::Buffer(mesh.vertices.size() * sizeof(GpuVertex), mesh.vertices.data(), 0);
    triangles_ = gl::Buffer(mesh.triangles.size() * sizeof(std::uint32_t), mesh.triangles.data(), 0);
    bits_ = gl::Buffer(std::size_t(bricks_per_tile) * slab_bytes, nullptr, 0);
    if (method == Method::Hybrid) {
        large_ = gl::Buffer(std::size_t(triangle_count_) * 4, nullptr, 0);
        draw_ = gl::Buffer(16, nullptr, GL_DYNAMIC_STORAGE_BIT);
    }
    if (method != Method::Triangle) {
        glNamedFramebufferParameteri(framebuffer_.id(), GL_FRAMEBUFFER_DEFAULT_WIDTH,
                                     std::max(grid.dims[0], std::max(grid.dims[1], grid.dims[2])));
        glNamedFramebufferParameteri(framebuffer_.id(), GL_FRAMEBUFFER_DEFAULT_HEIGHT,
                                     std::max(grid.dims[0], std::max(grid.dims[1], grid.dims[2])));
    }
    gl::checkGl("uploading the mesh");
}

const GlVoxelizer::Programs& GlVoxelizer::programsFor(bool voxel_list) {
    Programs& p = programs_by_list_[voxel_list ? 1 : 0];
    if (p.built)
        return p;
    if (method_ == Method::Triangle)
        p.triangle.program = &programs_.get({{GL_COMPUTE_SHADER, "hybrid/triangle_parallel.comp"}},
                                            definesFor(mode_, voxel_list, false), shader_dir_);
    if (method_ == Method::Hybrid)
        p.classify.program = &programs_.get({{GL_COMPUTE_SHADER, "hybrid/classify.comp"}},
                                            definesFor(mode_, voxel_list, false), shader_dir_);
    if (method_ != Method::Triangle)
        p.raster.program = &programs_.get({{GL_VERTEX_SHADER, "hybrid/fragment_parallel.vert"},
                                           {GL_GEOMETRY_SHADER, "hybrid/fragment_parallel.geom"},
                                           {GL_FRAGMENT_SHADER, "hybrid/fragment_parallel.frag"}},
                                          definesFor(mode_, voxel_list, method_ == Method::Hybrid), shader_dir_);
    for (Stage* stage : {&p.triangle, &p.classify, &p.raster})
        if (stage->program)
            stage->active = activeUniforms(*stage->program);
    p.built = true;
    return p;
}

template <typename Set>
void GlVoxelizer::setUniform(const Programs& programs, GLint location, const Set& set) const {
    for (const Stage* stage : {&programs.triangle, &programs.classify, &programs.raster})
        if (stage->program && (stage->active >> location & 1u))
            set(stage->program->id());
}

void GlVoxelizer::setRunUniforms(const Programs& p, double cutoff) const {
    const float side = float(std::max({grid_.dims[0], grid_.dims[1], grid_.dims[2]}));
    setUniform(p, HYVOX_LOC_GRID_DIMS, [&](GLuint id) {
        glProgramUniform3i(id, HYVOX_LOC_GRID_DIMS, grid_.dims[0], grid_.dims[1], grid_.dims[2]);
    });
    setUniform(p, HYVOX_LOC_TRIANGLE_COUNT,
               [&](GLuint id) { glProgramUniform1ui(id, HYVOX_LOC_TRIANGLE_COUNT, triangle_count_); });
    setUniform(p, HYVOX_LOC_CUTOFF, [&](GLuint id) { glProgramUniform1f(id, HYVOX_LOC_CUTOFF, float(cutoff)); });
    setUniform(p, HYVOX_LOC_VIEWPORT, [&](GLuint id) { glProgramUniform2f(id, HYVOX_LOC_VIEWPORT, side, side); });
    setUniform(p, HYVOX_LOC_CHUNK_SIDE,
               [&](GLuint id) { glProgramUniform1i(id, HYVOX_LOC_CHUNK_SIDE, tuning_.chunk_side); });
}

void GlVoxelizer::setTileUniforms(const Programs& p, const Tile& tile) const {
    setUniform(p, HYVOX_LOC_SLAB, [&](GLuint id) {
        glProgramUniform2i(id, HYVOX_LOC_SLAB, tile.brick_x0 * 8, std::min(grid_.dims[0], tile.brick_x1 * 8));
    });
}

void GlVoxelizer::runTile(const Tile& tile, const Programs& p, double cutoff, PassTimes& times) {
    bits_.clearToZero();
    vertices_.bindBase(GL_SHADER_STORAGE_BUFFER, HYVOX_SSBO_VERTICES);
    triangles_.bindBase(GL_SHADER_STORAGE_BUFFER, HYVOX_SSBO_TRIANGLES);
    bits_.bindBase(GL_SHADER_STORAGE_BUFFER, HYVOX_SSBO_BITS);
    if (method_ == Method::Hybrid) {
        large_.bindBase(GL_SHADER_STORAGE_BUFFER, HYVOX_SSBO_LARGE);
        draw_.bindBase(GL_SHADER_STORAGE_BUFFER, HYVOX_SSBO_DRAW);
        const std::uint32_t command[4] = {0, 1, 0, 0};  // count, instanceCount, first, baseInstance
        draw_.upload(0, sizeof(command), command);
    }
    const bool pass1 = method_ != Method::Fragment, pass2 = method_ != Method::Triangle;
    gl::PassTimer timer1(tuning_.wall_timing), timer2(tuning_.wall_timing);
    if (pass1) {
        const gl::Program& program = method_ == Method::Triangle ? *p.triangle.program : *p.classify.program;
        program.use();
        timer1.begin();
        gl::dispatchPerItem(program, triangle_count_, chunksFor(cutoff));
        timer1.end();
    }
    if (pass2) {
        glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
        p.raster.program->use();
        glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
        const GLint side = std::max({grid_.dims[0], grid_.dims[1], grid_.dims[2]});
        glViewport(0, 0, side, side);
        glDisable(GL_DEPTH_TEST);
        glDisable(GL_CULL_FACE);
        for (int i = 0; i < 4; ++i)
            glEnable(GL_CLIP_DISTANCE0 + i);
        glBindVertexArray(empty_vao_.id());
        timer2.begin();
        if (method_ == Method::Hybrid) {
            glBindBuffer(GL_DRAW_INDIRECT_BUFFER, draw_.id());
            glDrawArraysIndirect(GL_TRIANGLES, nullptr);
            glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
        } else {
            glDrawArrays(GL_TRIANGLES, 0, GLsizei(triangle_count_) * 3);
        }
        timer2.end();
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
    }
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
    if (pass1)
        times.pass1_gpu_ms += timer1.milliseconds();
    if (pass2)
        times.pass2_gpu_ms += timer2.milliseconds();
    if (method_ == Method::Hybrid) {
        std::uint32_t vertex_count = 0;
        draw_.download(0, 4, &vertex_count);
        times.large_triangles += vertex_count / 3;
    }
    ++times.tiles;
    gl::checkGl(toString(method_));
}

std::uint32_t GlVoxelizer::chunksFor(double cutoff) const {
    if (extents_.empty()) return 1;
    // Only triangles pass 1 voxelizes count: all for `triangle`, the small ones for `hybrid`
    // (with a margin for the shader's float area against this double one).
    const double small_limit = method_ == Method::Triangle ? INFINITY : cutoff * 1.001 + 1e-3;
    float largest = 0;
    for (std::size_t t = 0; t < extents_.size(); ++t)
        if (areas_[t] <= small_limit) largest = std::max(largest, extents_[t]);
    const double grid_side = double(std::max({grid_.dims[0], grid_.dims[1], grid_.dims[2]}));
    const double per_side = std::ceil((std::min(grid_side, double(largest)) + 2.0) / tuning_.chunk_side);
    return std::uint32_t(std::min(65535.0, per_side * per_side));
}

PassTimes GlVoxelizer::run(double cutoff, BitGrid* out, const std::function<void()>& before_tile) {
    const Programs& programs = programsFor(false);
    setRunUniforms(programs, cutoff);
    PassTimes times;
    for (const Tile& tile : tiles_) {
        if (before_tile)
            before_tile();
        setTileUniforms(programs, tile);
        runTile(tile, programs, cutoff, times);
        if (out) {
            Stopwatch watch;
            // Tiles are whole slabs of bricks: contiguous in the leaf layout, copied in place.
            const std::size_t offset = std::size_t(tile.brick_x0) * bricks_[1] * bricks_[2] * kBrickBytes;
            const std::size_t bytes =
                std::size_t(tile.brick_x1 - tile.brick_x0) * bricks_[1] * bricks_[2] * kBrickBytes;
            bits_.download(0, bytes, reinterpret_cast<unsigned char*>(out->data()) + offset);
            gl::checkGl("reading back the bit grid");
            times.readback_ms += watch.elapsedMs();
        }
    }
    return times;
}

std::vector<std::array<std::int32_t, 3>> GlVoxelizer::runVoxelList(double cutoff, PassTimes* times_out) {
    const Programs& programs = programsFor(true);
    setRunUniforms(programs, cutoff);
    PassTimes times;
    std::vector<std::array<std::int32_t, 3>> voxels;
    // The list is one storage block (16 bytes of count, then 12 per voxel), unlike the bit
    // grid not tiled; the shader's 32-bit word indices allow at most 2^30 entries besides.
    const std::uint64_t block_bytes = std::uint64_t(std::max<GLint64>(glLimit(GL_MAX_SHADER_STORAGE_BLOCK_SIZE), 16));
    const std::uint32_t max_capacity = std::uint32_t(std::min<std::uint64_t>((block_bytes - 16) / 12, 1u << 30));
    // A first guess of the list's length; a tile that overflows is run again with room for
    // the count it reported (the count keeps rising past the capacity).
    std::uint32_t capacity = std::min(
        max_capacity,
        std::uint32_t(std::clamp<std::uint64_t>(std::uint64_t(triangle_count_) * 4u, 1u << 16, 1u << 24)));
    for (const Tile& tile : tiles_) {
        setTileUniforms(programs, tile);
        for (;;) {
            if (voxel_list_.size() < 16 + std::size_t(capacity) * 12)
                voxel_list_ = gl::Buffer(16 + std::size_t(capacity) * 12, nullptr, GL_DYNAMIC_STORAGE_BIT);
            const std::uint32_t zero = 0;
            voxel_list_.upload(0, 4, &zero);
            voxel_list_.bindBase(GL_SHADER_STORAGE_BUFFER, HYVOX_SSBO_VOXEL_LIST);
            setUniform(programs, HYVOX_LOC_LIST_CAPACITY,
                       [&](GLuint id) { glProgramUniform1ui(id, HYVOX_LOC_LIST_CAPACITY, capacity); });
            PassTimes attempt;
            runTile(tile, programs, cutoff, attempt);
            times.pass1_gpu_ms += attempt.pass1_gpu_ms;  // a retried run's work took time too
            times.pass2_gpu_ms += attempt.pass2_gpu_ms;
            std::uint32_t count = 0;
            voxel_list_.download(0, 4, &count);
            if (count > capacity) {
                if (count > max_capacity)
                    throw ResourceError("the voxel list needs " + std::to_string(count) +
                                        " voxels in one tile, more than the " + std::to_string(max_capacity) +
                                        " that fit this GL device's storage-block limit of " +
                                        std::to_string(block_bytes >> 20) + " MiB; use a larger voxel size");
                capacity = count;
                continue;
            }
            times.large_triangles += attempt.large_triangles;
            times.tiles += attempt.tiles;
            std::vector<std::uint32_t> entries(std::size_t(count) * 3);
            if (count)
                voxel_list_.download(16, entries.size() * 4, entries.data());
            for (std::size_t i = 0; i < count; ++i)
                voxels.push_back(
                    {std::int32_t(entries[3 * i]), std::int32_t(entries[3 * i + 1]), std::int32_t(entries[3 * i + 2])});
            break;
        }
    }
    gl::checkGl("reading back the voxel list");
    if (times_out)
        *times_out = times;
    return voxels;
}

}  // namespace hyvox::hybrid
