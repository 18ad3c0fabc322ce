// SPDX-License-Identifier: GPL-3.0-or-later
#include "tessellation/gl_tessellation.h"

#include <epoxy/gl.h>

#include <algorithm>

#include "gl/active_uniforms.h"
#include "gl/binding_points.h"
#include "gl/compute_dispatch.h"
#include "gl/gl_debug.h"
#include "gl/gl_limits.h"
#include "gl/gl_objects.h"
#include "gl/gl_tuning.h"
#include "gl/gl_worker.h"
#include "gl/pass_timer.h"
#include "gl/shader_library.h"
#include "hyvox/errors.h"
#include "tessellation/binding_points.h"

namespace hyvox::tessellation {
namespace {

// Patches per draw call: keeps gl_VertexID far from overflow and lets a cancel land between draws.
constexpr std::uint64_t kPatchesPerDraw = 1u << 22;

std::string definesFor(const GpuTessellationInput& in) {
    std::string defines;
    if (in.pn_triangles) defines += "#define PN_TRIANGLES 1\n";
    if (!in.heights.empty()) defines += "#define DISPLACEMENT 1\n";
    if (in.counts) defines += "#define COUNTS 1\n";
    if (in.values) defines += in.values->defines();
    return defines;
}

template <typename T>
gl::Buffer upload(const std::vector<T>& data) {
    return gl::Buffer(data.size() * sizeof(T), data.empty() ? nullptr : data.data());
}

bool brickTouched(const BitGrid& bits, std::size_t brick) {
    const std::uint64_t* w = bits.data() + brick * BitGrid::kWordsPerBrick;
    for (int k = 0; k < BitGrid::kWordsPerBrick; ++k)
        if (w[k]) return true;
    return false;
}

struct Counters {
    std::uint32_t points, clipped, blocks;
};

// One complete draw of every patch into freshly cleared buffers.
struct Programs {
    gl::ActiveProgram whole;  // compute: triangles left whole
    gl::ActiveProgram draw;   // vertex → tessellation → geometry
    template <typename Set>
    void setUniform(GLint location, const Set& set) const {
        gl::setUniform({&whole, &draw}, location, set);
    }
};
struct PatchLists {
    const gl::Buffer& whole;
    const gl::Buffer& direct;
};
// Per-voxel counts and (with attributes) value sums, both indexed by the brick's block.
struct Pools {
    gl::Buffer counts;
    gl::Buffer values;
};

Counters drawAll(const GpuTessellationInput& in, const Programs& programs, const PatchLists& lists,
                 const gl::Buffer& bits, const gl::Buffer& counters, const gl::Buffer& table, const Pools& pools,
                 std::uint32_t pool_blocks, bool prefilled, const gl::GlTuning& tuning, GpuTessellationOutput& out) {
    bits.clearToZero();
    counters.clearToZero();
    if (in.counts) {
        if (!prefilled) table.clearToZero();
        pools.counts.clearToZero();
        if (in.values) pools.values.clearToZero();
    }
    // The uniforms both programs share (each set where the program uses it).
    programs.setUniform(HYVOX_LOC_GRID_DIMS, [&](GLuint id) {
        glProgramUniform3i(id, HYVOX_LOC_GRID_DIMS, in.dims[0], in.dims[1], in.dims[2]);
    });
    if (!in.heights.empty()) {
        programs.setUniform(HYVOX_TESS_LOC_HEIGHT_SIZE, [&](GLuint id) {
            glProgramUniform2i(id, HYVOX_TESS_LOC_HEIGHT_SIZE, in.height_width, in.height_height);
        });
        programs.setUniform(HYVOX_TESS_LOC_DISPLACE, [&](GLuint id) {
            glProgramUniform2f(id, HYVOX_TESS_LOC_DISPLACE, float(in.strength_voxels), float(in.midlevel));
        });
    }
    if (in.counts) {
        programs.setUniform(HYVOX_TESS_LOC_POOL_BLOCKS,
                            [&](GLuint id) { glProgramUniform1ui(id, HYVOX_TESS_LOC_POOL_BLOCKS, pool_blocks); });
        programs.setUniform(HYVOX_TESS_LOC_PREFILLED,
                            [&](GLuint id) { glProgramUniform1ui(id, HYVOX_TESS_LOC_PREFILLED, prefilled ? 1u : 0u); });
    }
    bits.bindBase(GL_SHADER_STORAGE_BUFFER, HYVOX_SSBO_BITS);
    counters.bindBase(GL_SHADER_STORAGE_BUFFER, HYVOX_TESS_SSBO_COUNTERS);
    table.bindBase(GL_SHADER_STORAGE_BUFFER, HYVOX_TESS_SSBO_BRICK_TABLE);
    pools.counts.bindBase(GL_SHADER_STORAGE_BUFFER, HYVOX_TESS_SSBO_COUNT_POOL);
    if (in.values) pools.values.bindBase(GL_SHADER_STORAGE_BUFFER, HYVOX_TESS_SSBO_VALUE_POOL);

    // Pass 0: one point per triangle the tessellator would leave whole.
    gl::PassTimer whole_timer(tuning.wall_timing);
    {
        const gl::Program& whole = *programs.whole.program();
        whole.use();
        lists.whole.bindBase(GL_SHADER_STORAGE_BUFFER, HYVOX_TESS_SSBO_PATCHES);
        const std::uint64_t count = in.plan.whole.size();
        gl::setUniform({&programs.whole}, HYVOX_TESS_LOC_SPLIT_COUNT,
                       [&](GLuint id) { glProgramUniform1ui(id, HYVOX_TESS_LOC_SPLIT_COUNT, GLuint(count)); });
        whole_timer.begin();
        gl::dispatchPerItem(whole, count);
        whole_timer.end();
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        lists.direct.bindBase(GL_SHADER_STORAGE_BUFFER, HYVOX_TESS_SSBO_PATCHES);
    }

    programs.draw.program()->use();
    auto setDrawUniform = [&](GLint location, const auto& set) { gl::setUniform({&programs.draw}, location, set); };
    setDrawUniform(HYVOX_TESS_LOC_GAMMA,
                   [&](GLuint id) { glProgramUniform1f(id, HYVOX_TESS_LOC_GAMMA, float(in.gamma)); });
    setDrawUniform(HYVOX_TESS_LOC_MAX_LEVEL,
                   [&](GLuint id) { glProgramUniform1f(id, HYVOX_TESS_LOC_MAX_LEVEL, float(in.max_level)); });
    setDrawUniform(HYVOX_TESS_LOC_SPLIT_COUNT, [&](GLuint id) {
        glProgramUniform1ui(id, HYVOX_TESS_LOC_SPLIT_COUNT, GLuint(in.plan.splits.size() / 4));
    });

    gl::PassTimer direct_timer(tuning.wall_timing), split_timer(tuning.wall_timing);
    // A patch makes at most max_level² points, so a draw of `per_draw` patches makes at most
    // about 8M (a fraction of a second on a software device). Draws are queued one ahead of
    // the GPU: before the next, the one before last must have finished, and the interrupter
    // is polled while waiting, so a cancel stops the run within about one draw.
    const std::uint64_t level2 = std::uint64_t(std::max(in.max_level, 1)) * std::uint64_t(std::max(in.max_level, 1));
    const std::uint64_t per_draw = std::clamp<std::uint64_t>((8ull << 20) / level2, 1, kPatchesPerDraw);
    auto interrupted = [&] { return in.interrupter && in.interrupter->wasInterrupted(); };
    // True when the fence signalled, false when the interrupter asked to stop first.
    auto waitFor = [&](GLsync fence) {
        for (;;) {
            const GLenum state = glClientWaitSync(fence, GL_SYNC_FLUSH_COMMANDS_BIT, 2'000'000);  // 2 ms
            if (state == GL_ALREADY_SIGNALED || state == GL_CONDITION_SATISFIED) return true;
            if (state == GL_WAIT_FAILED) throw BackendError("waiting for a tessellation draw failed");
            if (interrupted()) return false;
        }
    };
    auto drawPatches = [&](GLuint mode, std::uint64_t patches, gl::PassTimer& timer) {
        setDrawUniform(HYVOX_TESS_LOC_SPLIT_MODE,
                       [&](GLuint id) { glProgramUniform1ui(id, HYVOX_TESS_LOC_SPLIT_MODE, mode); });
        timer.begin();
        bool cancelled = interrupted();
        GLsync previous = nullptr;
        for (std::uint64_t base = 0; base < patches && !cancelled; base += per_draw) {
            const std::uint64_t count = std::min(per_draw, patches - base);
            setDrawUniform(HYVOX_TESS_LOC_PATCH_BASE,
                           [&](GLuint id) { glProgramUniform1ui(id, HYVOX_TESS_LOC_PATCH_BASE, GLuint(base)); });
            // One instance per patch where plain patch draws are assembled wrongly (GlTuning).
            if (tuning.tess_instanced)
                glDrawArraysInstanced(GL_PATCHES, 0, 3, GLsizei(count));
            else
                glDrawArrays(GL_PATCHES, 0, GLsizei(3 * count));
            GLsync fence = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
            if (previous) {
                cancelled = !waitFor(previous);
                glDeleteSync(previous);
            }
            previous = fence;
            cancelled = cancelled || interrupted();
        }
        if (previous) glDeleteSync(previous);
        timer.end();
        if (cancelled) throw Cancelled();
    };
    drawPatches(0, in.plan.direct.size(), direct_timer);
    drawPatches(1, in.plan.split_patches, split_timer);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
    gl::checkGl("tessellation draw");
    out.whole_gpu_ms += whole_timer.milliseconds();
    out.direct_gpu_ms += direct_timer.milliseconds();
    out.split_gpu_ms += split_timer.milliseconds();
    Counters c{};
    counters.download(0, sizeof(c), &c);
    return c;
}

}  // namespace

int maxTessellationLevel(const std::string& device) {
    return gl::GlWorker::get(device).run([] {
        GLint level = 0;
        glGetIntegerv(GL_MAX_TESS_GEN_LEVEL, &level);
        return int(level);
    });
}

GpuTessellationOutput runGpuTessellation(const GpuTessellationInput& in, BitGrid& bits) {
    gl::GlWorker& worker = gl::GlWorker::get(in.gl.device);
    return worker.run([&] {
        GpuTessellationOutput out;
        const gl::GlTuning tuning = gl::GlTuning::forDevice(worker.device().software, in.gl);
        const GLint64 max_ssbo = gl::glLimit(GL_MAX_SHADER_STORAGE_BLOCK_SIZE);
        if (GLint64(bits.byteSize()) > max_ssbo)
            throw ResourceError("the " + std::to_string(bits.byteSize() >> 20) +
                                " MiB bit grid exceeds this GL device's " + std::to_string(max_ssbo >> 20) +
                                " MiB storage-buffer limit; lower the resolution");
        const std::string defines = definesFor(in);
        const Programs programs{
            gl::ActiveProgram(worker.programs().get({{GL_COMPUTE_SHADER, "tessellation/whole_triangles.comp"}}, defines,
                                                    in.gl.shader_dir)),
            gl::ActiveProgram(worker.programs().get({{GL_VERTEX_SHADER, "tessellation/patch.vert"},
                                                     {GL_TESS_CONTROL_SHADER, "tessellation/patch.tesc"},
                                                     {GL_TESS_EVALUATION_SHADER, "tessellation/patch.tese"},
                                                     {GL_GEOMETRY_SHADER, "tessellation/inject.geom"}},
                                                    defines, in.gl.shader_dir))};

        const gl::Buffer vertices = upload(in.mesh.vertices);
        const gl::Buffer triangles = upload(in.mesh.triangles);
        const gl::Buffer normals = upload(in.normals);
        const gl::Buffer uvs = upload(in.uvs);
        const gl::Buffer whole = upload(in.plan.whole);
        const gl::Buffer direct = upload(in.plan.direct);
        const gl::Buffer splits = upload(in.plan.splits);
        const gl::Buffer heights = upload(in.heights);
        const std::vector<float> no_values;
        const gl::Buffer corner_values = upload(in.values ? in.values->corners : no_values);
        const Texture* texture = in.values ? in.values->texture : nullptr;
        const gl::Buffer texels = upload(texture ? texture->texels : no_values);
        for (const auto& [buffer, what] :
             {std::pair{&corner_values, "the triangles' corner attributes"}, std::pair{&texels, "the texture"}})
            if (GLint64(buffer->size()) > max_ssbo)
                throw ResourceError(std::string(what) + " (" + std::to_string(buffer->size() >> 20) +
                                    " MiB) exceed this GL device's " + std::to_string(max_ssbo >> 20) +
                                    " MiB storage-buffer limit");
        vertices.bindBase(GL_SHADER_STORAGE_BUFFER, HYVOX_SSBO_VERTICES);
        triangles.bindBase(GL_SHADER_STORAGE_BUFFER, HYVOX_SSBO_TRIANGLES);
        normals.bindBase(GL_SHADER_STORAGE_BUFFER, HYVOX_TESS_SSBO_NORMALS);
        uvs.bindBase(GL_SHADER_STORAGE_BUFFER, HYVOX_TESS_SSBO_UVS);
        splits.bindBase(GL_SHADER_STORAGE_BUFFER, HYVOX_TESS_SSBO_SPLITS);
        heights.bindBase(GL_SHADER_STORAGE_BUFFER, HYVOX_TESS_SSBO_HEIGHTS);
        corner_values.bindBase(GL_SHADER_STORAGE_BUFFER, HYVOX_TESS_SSBO_CORNER_VALUES);
        texels.bindBase(GL_SHADER_STORAGE_BUFFER, HYVOX_TESS_SSBO_TEXELS);
        if (texture)
            programs.setUniform(HYVOX_TESS_LOC_TEXTURE_SIZE, [&](GLuint id) {
                glProgramUniform3i(id, HYVOX_TESS_LOC_TEXTURE_SIZE, texture->width, texture->height, texture->channels);
            });

        const gl::Buffer bit_buffer(bits.byteSize(), nullptr);
        const gl::Buffer counters(4 * sizeof(std::uint32_t), nullptr);
        const std::size_t brick_count = bits.brickCount();
        const gl::Buffer table(in.counts ? brick_count * sizeof(std::uint32_t) : 0, nullptr);
        const PatchLists lists{whole, direct};
        gl::VertexArray no_attributes;
        glBindVertexArray(no_attributes.id());
        // A surfaceless context has no complete default framebuffer, and draws need one even
        // with the rasterizer off: an attachment-less 1×1 framebuffer will do.
        gl::Framebuffer no_attachments;
        glNamedFramebufferParameteri(no_attachments.id(), GL_FRAMEBUFFER_DEFAULT_WIDTH, 1);
        glNamedFramebufferParameteri(no_attachments.id(), GL_FRAMEBUFFER_DEFAULT_HEIGHT, 1);
        glBindFramebuffer(GL_FRAMEBUFFER, no_attachments.id());
        glPatchParameteri(GL_PATCH_VERTICES, 3);
        glEnable(GL_RASTERIZER_DISCARD);  // points go to buffers, never to pixels
        struct RestoreState {
            ~RestoreState() {
                glDisable(GL_RASTERIZER_DISCARD);
                glBindFramebuffer(GL_FRAMEBUFFER, 0);
                glBindVertexArray(0);
                glUseProgram(0);
            }
        } restore;

        // Counts, first try: blocks handed out on first touch, the pool sized from the plan's
        // brick estimate (doubled, plus a margin) with room for the blocks lost races take
        // (lanes of one SIMD group reaching a new brick together each take one), never more
        // than every brick plus that room. If the pool ran out at all, some
        // point may have dropped its count (even in a brick another point later gave a
        // block), so the bits of that run, which say exactly which bricks are touched, are
        // numbered on the host and everything is drawn again into that table, which needs no
        // allocation and cannot run out.
        // Attribute sums take valueWordsPerBlock() more words per block in a buffer of their own.
        const std::uint64_t value_words = in.values ? valueWordsPerBlock(in.values->channels()) : 0;
        const std::uint64_t block_bytes = (512 + value_words) * sizeof(std::uint32_t);
        std::uint64_t cap_blocks = std::min<std::uint64_t>(in.memory_budget_bytes / block_bytes,
                                                           std::uint64_t(max_ssbo) / (512 * sizeof(std::uint32_t)));
        if (value_words) cap_blocks = std::min<std::uint64_t>(cap_blocks, std::uint64_t(max_ssbo) / (value_words * 4));
        cap_blocks = std::max<std::uint64_t>(cap_blocks, 1);
        auto poolFor = [&](std::uint64_t blocks) {
            if (blocks > cap_blocks)
                throw ResourceError(
                    std::string(in.values ? "the point counts and attribute sums" : "the point counts") + " need " +
                    std::to_string((blocks * block_bytes) >> 20) +
                    " MiB, more than this GL device and the memory budget allow (" +
                    std::to_string((cap_blocks * block_bytes) >> 20) + " MiB); " +
                    (in.values ? "lower tile_size (a tile's sums take blocks only for its own bricks) or the resolution"
                               : "turn counts off or lower the resolution"));
            return Pools{gl::Buffer(in.counts ? blocks * 512 * sizeof(std::uint32_t) : 0, nullptr),
                         gl::Buffer(blocks * value_words * sizeof(std::uint32_t), nullptr)};
        };
        const std::uint32_t first_blocks = std::uint32_t(
            std::min<std::uint64_t>({2 * (in.plan.brick_estimate + 64) + 256, brick_count + 256, cap_blocks}));
        Pools pools = poolFor(in.counts ? first_blocks : 1);
        out.runs = 1;
        Counters c = drawAll(in, programs, lists, bit_buffer, counters, table, pools, first_blocks, false, tuning, out);
        bit_buffer.download(0, bits.byteSize(), bits.data());
        if (in.counts) {
            out.brick_blocks.resize(brick_count);
            table.download(0, brick_count * sizeof(std::uint32_t), out.brick_blocks.data());
            std::uint32_t used = c.blocks;
            if (c.blocks > first_blocks) {
                used = 0;
                for (std::size_t b = 0; b < brick_count; ++b) out.brick_blocks[b] = brickTouched(bits, b) ? ++used : 0;
                table.upload(0, brick_count * sizeof(std::uint32_t), out.brick_blocks.data());
                pools = poolFor(used);
                out.runs = 2;
                c = drawAll(in, programs, lists, bit_buffer, counters, table, pools, used, true, tuning, out);
            }
            out.count_pool.resize(std::size_t(used) * 512);
            pools.counts.download(0, out.count_pool.size() * sizeof(std::uint32_t), out.count_pool.data());
            if (value_words) {
                out.value_pool.resize(std::size_t(used) * value_words);
                pools.values.download(0, out.value_pool.size() * sizeof(std::uint32_t), out.value_pool.data());
            }
        }
        out.points = c.points;
        out.clipped = c.clipped;
        return out;
    });
}

}  // namespace hyvox::tessellation
