// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// How the GL methods adapt to the device they run on: the device's quirks (Mesa's llvmpipe)
// and the caller's GlOptions, decided once per run in one place for both GL methods.
#include "hyvox/options.h"

namespace hyvox::gl {

struct GlTuning {
    // Time passes by the CPU clock around glFinish instead of GL_TIME_ELAPSED queries: for
    // Mesa's llvmpipe, whose timer queries miss compute dispatches (they read ~0) and are
    // erratic for draws; its "GPU" is the CPU, so the wall clock measures the same work.
    // GlOptions::wall_timing asks for it on any device.
    bool wall_timing = false;
    // Columns per side of one compute invocation's share of a triangle (0 = the whole
    // triangle): llvmpipe stops any invocation after 65535 loop iterations in total, so it
    // needs chunks (see shaders/common/voxelize_triangle.glsl).
    int chunk_side = 0;
    // Tessellation: one instance of 3 vertices per patch instead of one plain patch draw.
    // Mesa's llvmpipe (22.3) assembles the patches of a plain glDrawArrays(GL_PATCHES) wrongly
    // beyond a few dozen per draw (gl_VertexID no longer matches the patch); the vertex
    // shader reads both. GlOptions::tess_instanced asks for it on any device.
    bool tess_instanced = false;

    static GlTuning forDevice(bool software, const GlOptions& options);
};

}  // namespace hyvox::gl
