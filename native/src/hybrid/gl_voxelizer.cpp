// SPDX-License-Identifier: GPL-3.0-or-later
#include "hybrid/gl_voxelizer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

#include "attributes/clip_to_voxel.h"
#include "gl/binding_points.h"
#include "gl/compute_dispatch.h"
#include "gl/gl_debug.h"
#include "gl/gl_limits.h"
#include "gl/pass_timer.h"
#include "hyvox/errors.h"

namespace hyvox::hybrid {
namespace {

using gl::glLimit;

// The clip's thresholds are the cpu method's (attributes/clip_to_voxel.h), written as GLSL
// double literals.
std::string clipConstants() {
    char text[160];
    std::snprintf(text, sizeof text, "#define HYVOX_TOUCH_AREA %.17gLF\n#define HYVOX_TOUCH_MARGIN %.17gLF\n",
                  attributes::kTouchArea, attributes::kTouchMargin);
    return text;
}

template <typename Output>
std::string definesFor(Mode mode, Output output, bool from_large_list) {
    return std::string("#define HYVOX_THIN ") + (mode == Mode::Thin ? "1" : "0") + "\n#define HYVOX_VOXEL_LIST " +
        (output == Output::VoxelList ? "1" : "0") + "\n#define HYVOX_ATTRIBUTE_PAIRS " +
        (output == Output::AttributePairs ? "1" : "0") + "\n#define HYVOX_FROM_LARGE_LIST " +
        (from_large_list ? "1" : "0") + "\n";
}

// std430 layout of Piece in shaders/hybrid/clip_pieces.comp.
struct GpuPiece {
    float area;
    float centroid[3];
    std::uint32_t kind;
};
static_assert(sizeof(GpuPiece) == 20, "must match the GLSL struct");
constexpr std::size_t kPairBytes = 16;   // uvec4: x, y, z, triangle
constexpr std::size_t kPairHeader = 16;  // the count, padded

// Per triangle: the largest side of its bounding box and its area projected on its dominant
// plane, in voxel units (llvmpipe's chunk count; see GlTuning::chunk_side).
void measureTriangles(const gl::GpuMesh& mesh, std::vector<float>& extent, std::vector<float>& area) {
    extent.resize(mesh.triangleCount());
    area.resize(mesh.triangleCount());
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        const gl::TriangleCorners p = gl::triangleCorners(mesh, t);
        double side = 0;
        for (int a = 0; a < 3; ++a)
            side = std::max(side, std::max({p[0][a], p[1][a], p[2][a]}) - std::min({p[0][a], p[1][a], p[2][a]}));
        extent[t] = float(side);
        area[t] = float(gl::projectedArea(p));
    }
}

}  // namespace

GlVoxelizer::GlVoxelizer(const gl::GpuMesh& mesh, const GridSpec& grid, Mode mode, Method method,
                         const std::string& shader_dir, gl::ProgramCache& programs, const gl::GlTuning& tuning,
                         std::uint64_t tile_bytes, std::uint64_t pair_list_bytes)
    : grid_(grid),
      mode_(mode),
      method_(method),
      shader_dir_(shader_dir),
      programs_(programs),
      triangle_count_(std::uint32_t(mesh.triangleCount())),
      tiling_(grid, tile_bytes),  // refuses a slab larger than a tile before anything is allocated
      pair_list_bytes_(pair_list_bytes),
      tuning_(tuning) {
    // Draw calls count vertices (3 per triangle) in a GLsizei.
    if (mesh.triangleCount() > 0x2aaaaaaaull)
        throw ResourceError("too many triangles for the GL methods (at most 715 million)");

    // Limits first, before any large allocation.
    if (method != Method::Triangle) {
        GLint viewport[2] = {0, 0};
        glGetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport);
        const GLint64 fb = std::min(glLimit(GL_MAX_FRAMEBUFFER_WIDTH), glLimit(GL_MAX_FRAMEBUFFER_HEIGHT));
        const GLint64 raster_limit = std::min<GLint64>({viewport[0], viewport[1], fb});
        if (grid.maxSide() > raster_limit)
            throw ResourceError("a " + grid.dimsText() + " grid exceeds this GL device's " +
                                std::to_string(raster_limit) + "-pixel framebuffer limit for method '" +
                                toString(method) + "'; use method 'triangle' or a larger voxel size");
    }
    // `fragment` too: its pass 1 voxelizes the triangles of zero projected area (planeless
    // ones: a needle across the grid needs as many chunks as any triangle).
    if (tuning_.chunk_side > 0) measureTriangles(mesh, extents_, areas_);

    vertices_ = gl::Buffer(mesh.vertices.size() * sizeof(gl::GpuVertex), mesh.vertices.data(), 0);
    triangles_ = gl::Buffer(mesh.triangles.size() * sizeof(std::uint32_t), mesh.triangles.data(), 0);
    bits_ = gl::Buffer(tiling_.maxTileBytes(), nullptr, 0);
    if (method == Method::Hybrid) {
        large_ = gl::Buffer(std::size_t(triangle_count_) * 4, nullptr, 0);
        draw_ = gl::Buffer(16, nullptr, GL_DYNAMIC_STORAGE_BIT);
    }
    if (method != Method::Triangle) {
        glNamedFramebufferParameteri(framebuffer_.id(), GL_FRAMEBUFFER_DEFAULT_WIDTH, grid.maxSide());
        glNamedFramebufferParameteri(framebuffer_.id(), GL_FRAMEBUFFER_DEFAULT_HEIGHT, grid.maxSide());
    }
    gl::checkGl("uploading the mesh");
}

const GlVoxelizer::Programs& GlVoxelizer::programsFor(Output output) {
    Programs& p = programs_by_output_[int(output)];
    if (p.built) return p;
    if (method_ == Method::Triangle)
        p.triangle = gl::ActiveProgram(programs_.get({{GL_COMPUTE_SHADER, "hybrid/triangle_parallel.comp"}},
                                                     definesFor(mode_, output, false), shader_dir_));
    if (method_ == Method::Hybrid)
        p.classify = gl::ActiveProgram(programs_.get({{GL_COMPUTE_SHADER, "hybrid/classify.comp"}},
                                                     definesFor(mode_, output, false), shader_dir_));
    if (method_ != Method::Triangle)
        p.raster = gl::ActiveProgram(programs_.get({{GL_VERTEX_SHADER, "hybrid/fragment_parallel.vert"},
                                                    {GL_GEOMETRY_SHADER, "hybrid/fragment_parallel.geom"},
                                                    {GL_FRAGMENT_SHADER, "hybrid/fragment_parallel.frag"}},
                                                   definesFor(mode_, output, method_ == Method::Hybrid), shader_dir_));
    if (output == Output::AttributePairs)
        p.clip = gl::ActiveProgram(
            programs_.get({{GL_COMPUTE_SHADER, "hybrid/clip_pieces.comp"}}, clipConstants(), shader_dir_));
    p.built = true;
    return p;
}

void GlVoxelizer::setRunUniforms(const Programs& p, double cutoff) const {
    const float side = float(grid_.maxSide());
    p.setUniform(HYVOX_LOC_GRID_DIMS, [&](GLuint id) {
        glProgramUniform3i(id, HYVOX_LOC_GRID_DIMS, grid_.dims[0], grid_.dims[1], grid_.dims[2]);
    });
    p.setUniform(HYVOX_LOC_TRIANGLE_COUNT,
                 [&](GLuint id) { glProgramUniform1ui(id, HYVOX_LOC_TRIANGLE_COUNT, triangle_count_); });
    p.setUniform(HYVOX_LOC_CUTOFF, [&](GLuint id) { glProgramUniform1f(id, HYVOX_LOC_CUTOFF, float(cutoff)); });
    p.setUniform(HYVOX_LOC_VIEWPORT, [&](GLuint id) { glProgramUniform2f(id, HYVOX_LOC_VIEWPORT, side, side); });
    p.setUniform(HYVOX_LOC_CHUNK_SIDE,
                 [&](GLuint id) { glProgramUniform1i(id, HYVOX_LOC_CHUNK_SIDE, tuning_.chunk_side); });
}

void GlVoxelizer::setTileUniforms(const Programs& p, const gl::BitTile& tile) const {
    const std::array<int, 2> slab = tiling_.voxelSlab(tile);
    p.setUniform(HYVOX_LOC_SLAB, [&](GLuint id) { glProgramUniform2i(id, HYVOX_LOC_SLAB, slab[0], slab[1]); });
}

void GlVoxelizer::runTile(const Programs& p, double cutoff, PassTimes& times) {
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
        const gl::Program& program = *(method_ == Method::Triangle ? p.triangle : p.classify).program();
        program.use();
        timer1.begin();
        gl::dispatchPerItem(program, triangle_count_, chunksFor(cutoff));
        timer1.end();
    }
    if (pass2) {
        glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
        p.raster.program()->use();
        glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
        glViewport(0, 0, grid_.maxSide(), grid_.maxSide());
        glDisable(GL_DEPTH_TEST);
        glDisable(GL_CULL_FACE);
        for (int i = 0; i < 4; ++i) glEnable(GL_CLIP_DISTANCE0 + i);
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
    if (pass1) times.pass1_gpu_ms += timer1.milliseconds();
    if (pass2) times.pass2_gpu_ms += timer2.milliseconds();
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
    const double grid_side = double(grid_.maxSide());
    const double per_side = std::ceil((std::min(grid_side, double(largest)) + 2.0) / tuning_.chunk_side);
    return std::uint32_t(std::min(65535.0, per_side * per_side));
}

PassTimes GlVoxelizer::run(double cutoff, BitGrid* out, const std::function<void()>& before_tile) {
    const Programs& programs = programsFor(Output::Bits);
    setRunUniforms(programs, cutoff);
    PassTimes times;
    times.readback_ms = tiling_.run(bits_, out, [&](const gl::BitTile& tile) {
        if (before_tile) before_tile();
        setTileUniforms(programs, tile);
        runTile(programs, cutoff, times);
    });
    return times;
}

std::vector<std::array<std::int32_t, 3>> GlVoxelizer::runVoxelList(double cutoff, PassTimes* times_out) {
    const Programs& programs = programsFor(Output::VoxelList);
    setRunUniforms(programs, cutoff);
    PassTimes times;
    std::vector<std::array<std::int32_t, 3>> voxels;
    // The list is one storage block (16 bytes of count, then 12 per voxel), unlike the bit
    // grid not tiled; the shader's 32-bit word indices allow at most 2^30 entries besides.
    const std::uint64_t block_bytes = std::uint64_t(std::max<GLint64>(glLimit(GL_MAX_SHADER_STORAGE_BLOCK_SIZE), 16));
    const std::uint32_t max_capacity = std::uint32_t(std::min<std::uint64_t>((block_bytes - 16) / 12, 1u << 30));
    // A first guess of the list's length; a tile that overflows is run again with room for
    // the count it reported (the count keeps rising past the capacity).
    std::uint32_t capacity =
        std::min(max_capacity,
                 std::uint32_t(std::clamp<std::uint64_t>(std::uint64_t(triangle_count_) * 4u, 1u << 16, 1u << 24)));
    for (const gl::BitTile& tile : tiling_.tiles()) {
        setTileUniforms(programs, tile);
        for (;;) {
            if (voxel_list_.size() < 16 + std::size_t(capacity) * 12)
                voxel_list_ = gl::Buffer(16 + std::size_t(capacity) * 12, nullptr, GL_DYNAMIC_STORAGE_BIT);
            PassTimes attempt;
            const std::uint32_t count = runTileIntoList(programs, cutoff, voxel_list_, HYVOX_SSBO_VOXEL_LIST,
                                                        HYVOX_LOC_LIST_CAPACITY, capacity, times, attempt);
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
            if (count) voxel_list_.download(16, entries.size() * 4, entries.data());
            for (std::size_t i = 0; i < count; ++i)
                voxels.push_back(
                    {std::int32_t(entries[3 * i]), std::int32_t(entries[3 * i + 1]), std::int32_t(entries[3 * i + 2])});
            break;
        }
    }
    gl::checkGl("reading back the voxel list");
    if (times_out) *times_out = times;
    return voxels;
}

std::uint32_t GlVoxelizer::runTileIntoList(const Programs& programs, double cutoff, gl::Buffer& list, GLuint binding,
                                           GLint capacity_location, std::uint32_t capacity, PassTimes& times,
                                           PassTimes& attempt) {
    const std::uint32_t zero = 0;
    list.upload(0, 4, &zero);
    list.bindBase(GL_SHADER_STORAGE_BUFFER, binding);
    programs.setUniform(capacity_location, [&](GLuint id) { glProgramUniform1ui(id, capacity_location, capacity); });
    runTile(programs, cutoff, attempt);
    times.pass1_gpu_ms += attempt.pass1_gpu_ms;  // a retried run's work took time too
    times.pass2_gpu_ms += attempt.pass2_gpu_ms;
    std::uint32_t count = 0;
    list.download(0, 4, &count);
    return count;
}

std::optional<std::uint32_t> GlVoxelizer::runTilePairs(const Programs& programs, const gl::BitTile& tile, double cutoff,
                                                       PassTimes& times) {
    setTileUniforms(programs, tile);
    // The pairs and their pieces are one storage block each; the shader's 32-bit count and
    // indices allow at most 2^31 besides.
    std::uint64_t block_bytes = std::uint64_t(std::max<GLint64>(glLimit(GL_MAX_SHADER_STORAGE_BLOCK_SIZE), 64));
    if (pair_list_bytes_ > 0) block_bytes = std::max<std::uint64_t>(std::min(block_bytes, pair_list_bytes_), 64);
    const std::uint32_t max_capacity = std::uint32_t(
        std::min<std::uint64_t>({(block_bytes - kPairHeader) / kPairBytes, block_bytes / sizeof(GpuPiece), 1u << 31}));
    if (pair_capacity_ == 0)  // a first guess; a tile that overflows is run again with room for its count
        pair_capacity_ =
            std::min(max_capacity,
                     std::uint32_t(std::clamp<std::uint64_t>(std::uint64_t(triangle_count_) * 8u, 1u << 16, 1u << 24)));
    std::uint32_t count = 0;
    for (;;) {
        if (pairs_.size() < kPairHeader + std::size_t(pair_capacity_) * kPairBytes) {
            pairs_ =
                gl::Buffer(kPairHeader + std::size_t(pair_capacity_) * kPairBytes, nullptr, GL_DYNAMIC_STORAGE_BIT);
            pieces_ = gl::Buffer(std::size_t(pair_capacity_) * sizeof(GpuPiece), nullptr, 0);
        }
        PassTimes attempt;
        count = runTileIntoList(programs, cutoff, pairs_, HYVOX_SSBO_PAIRS, HYVOX_LOC_PAIR_CAPACITY, pair_capacity_,
                                times, attempt);
        if (count <= pair_capacity_) {
            times.large_triangles += attempt.large_triangles;
            times.tiles += attempt.tiles;
            break;
        }
        if (count > max_capacity) {
            if (tile.brick_x1 - tile.brick_x0 > 1) return std::nullopt;  // the caller halves the tile
            throw ResourceError("colour and normal voxels need " + std::to_string(count) +
                                " triangle/voxel pairs in one 8-voxel slab, more than the " +
                                std::to_string(max_capacity) + " that fit the pair list's " +
                                std::to_string(block_bytes) +
                                " bytes (the GL device's storage-block limit, or gl_pair_list_bytes); use a larger "
                                "voxel size");
        }
        pair_capacity_ = count;
    }
    if (count == 0) return 0;
    pieces_.bindBase(GL_SHADER_STORAGE_BUFFER, HYVOX_SSBO_PIECES);
    const gl::Program& clip = *programs.clip.program();
    clip.use();
    if (programs.clip.uses(HYVOX_LOC_PAIR_COUNT)) glProgramUniform1ui(clip.id(), HYVOX_LOC_PAIR_COUNT, count);
    gl::PassTimer timer(tuning_.wall_timing);
    timer.begin();
    gl::dispatchPerItem(clip, count, 1);
    timer.end();
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    times.clip_gpu_ms += timer.milliseconds();
    return count;
}

PassTimes GlVoxelizer::runPieces(double cutoff, BitGrid* out, std::vector<VoxelPiece>& pieces,
                                 const std::function<void()>& before_tile) {
    const Programs& programs = programsFor(Output::AttributePairs);
    setRunUniforms(programs, cutoff);
    PassTimes times;
    std::vector<std::uint32_t> pair_words;
    std::vector<GpuPiece> clipped;
    // Tiles to run, last first: a tile whose pairs exceed a storage block is replaced by its halves.
    std::vector<gl::BitTile> todo(tiling_.tiles().rbegin(), tiling_.tiles().rend());
    while (!todo.empty()) {
        const gl::BitTile tile = todo.back();
        todo.pop_back();
        if (before_tile) before_tile();
        const std::optional<std::uint32_t> count = runTilePairs(programs, tile, cutoff, times);
        if (!count) {
            const int middle = (tile.brick_x0 + tile.brick_x1) / 2;
            todo.push_back({middle, tile.brick_x1});
            todo.push_back({tile.brick_x0, middle});
            continue;
        }
        if (out) times.readback_ms += tiling_.readBack(bits_, tile, *out);
        pair_words.resize(std::size_t(*count) * 4);
        clipped.resize(*count);
        if (*count) {
            pairs_.download(kPairHeader, pair_words.size() * 4, pair_words.data());
            pieces_.download(0, clipped.size() * sizeof(GpuPiece), clipped.data());
        }
        gl::checkGl("reading back the clipped pieces");
        pieces.reserve(pieces.size() + *count);
        for (std::size_t i = 0; i < *count; ++i) {
            const GpuPiece& g = clipped[i];
            if (g.kind == HYVOX_PIECE_NONE) continue;
            const std::uint32_t* w = &pair_words[4 * i];
            pieces.push_back({{std::int32_t(w[0]), std::int32_t(w[1]), std::int32_t(w[2])},
                              w[3],
                              g.area,
                              {g.centroid[0], g.centroid[1], g.centroid[2]},
                              g.kind == HYVOX_PIECE_MARGIN});
        }
    }
    return times;
}

}  // namespace hyvox::hybrid
