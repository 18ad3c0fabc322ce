// SPDX-License-Identifier: GPL-3.0-or-later
// The entry point of the plugin libhyvox_gl_methods.so: the GL methods' table
// (core/gl_methods.h) over the GL layer, the hybrid and the tessellation backends.
#include "core/gl_methods.h"

#include "gl/device_limits.h"
#include "gl/egl_device.h"
#include "gl/object_counts.h"
#include "tessellation/point_values.h"

namespace hyvox {
namespace {

std::vector<GlDevice> listDevices() {
    std::vector<GlDevice> out;
    for (const auto& d : gl::listEglDevices()) out.push_back({d.index, d.name, d.software});
    return out;
}

GlObjectCounts objectCounts() {
    auto count = [](gl::GlKind kind) { return gl::object_counts[int(kind)].load(std::memory_order_relaxed); };
    GlObjectCounts counts;
    counts.buffers = count(gl::GlKind::Buffer);
    counts.vertex_arrays = count(gl::GlKind::VertexArray);
    counts.framebuffers = count(gl::GlKind::Framebuffer);
    counts.programs = count(gl::GlKind::Program);
    counts.shaders = count(gl::GlKind::Shader);
    counts.queries = count(gl::GlKind::Query);
    return counts;
}

std::uint64_t tessellationTileBytes(const std::string& device, std::uint64_t budget, int channels) {
    const std::uint64_t block = gl::maxStorageBlockBytes(device);
    return channels > 0 ? tessellation::tileBitBytesForSums(block, budget, channels) : block;
}

// Each entry reports what it throws instead of letting it cross into the host
// (core/plugin_fault.h).
const GlMethodsTable table{guardedEntry<&runHybridBackend>, guardedEntry<&runTessellationBackend>,
                           guardedEntry<&tessellationTileBytes>, guardedEntry<&listDevices>,
                           guardedEntry<&objectCounts>};

}  // namespace
}  // namespace hyvox

extern "C" HYVOX_PLUGIN_ENTRY const hyvox::GlMethodsTable* hyvox_gl_methods() { return &hyvox::table; }
