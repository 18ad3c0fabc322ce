// SPDX-License-Identifier: GPL-3.0-or-later
#include "gl/live_objects.h"

#include "hyvox/gl_devices.h"

namespace hyvox {

GlObjectCounts liveGlObjects() {
    auto live = [](gl::GlKind kind) { return gl::live_gl_objects[int(kind)].load(std::memory_order_relaxed); };
    GlObjectCounts counts;
    counts.buffers = live(gl::GlKind::Buffer);
    counts.vertex_arrays = live(gl::GlKind::VertexArray);
    counts.framebuffers = live(gl::GlKind::Framebuffer);
    counts.programs = live(gl::GlKind::Program);
    counts.shaders = live(gl::GlKind::Shader);
    counts.queries = live(gl::GlKind::Query);
    return counts;
}

}  // namespace hyvox
