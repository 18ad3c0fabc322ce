// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The GL devices the GL methods can run on, so front ends can choose before voxelizing
// (the add-on picks a GL method automatically only for hardware devices).
#include <string>
#include <vector>

namespace hyvox {

struct GlDevice {
    int index = -1;         // the value GlOptions::device / HYVOX_GL_DEVICE takes to pick it
    std::string name;       // DRM node (e.g. /dev/dri/renderD128) or "software"
    bool software = false;  // Mesa's software rasterizer (llvmpipe): works, but slower than cpu
};

// Every EGL device of the process. Creates no context; empty when EGL has no device platform.
std::vector<GlDevice> listGlDevices();

// A diagnostic: the GL objects alive in the process now, by kind (the GL methods' programs
// stay cached per worker context; everything else lives for one run). The soak test checks
// these stay flat over hundreds of runs.
struct GlObjectCounts {
    long buffers = 0, vertex_arrays = 0, framebuffers = 0, programs = 0, shaders = 0, queries = 0;
};
GlObjectCounts liveGlObjects();

}  // namespace hyvox
