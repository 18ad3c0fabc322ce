// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file
/// The GL devices the GL methods can run on, so front ends can choose before voxelizing
/// (the add-on picks a GL method automatically only for hardware devices). Both queries go
/// through the GL methods' plugin (libhyvox_gl_methods.so).
#include <string>
#include <vector>

namespace hyvox {

/// One EGL device.
struct GlDevice {
    int index = -1;         ///< the value GlOptions::device / HYVOX_GL_DEVICE takes to pick it
    std::string name;       ///< DRM node (e.g. /dev/dri/renderD128) or "software"
    bool software = false;  ///< Mesa's software rasterizer (llvmpipe): works, but slower than cpu
};

/// Every EGL device of the process. Creates no context; empty when EGL has no device platform.
/// Loads the GL plugin. Thread-safe.
/// @throws BackendError the GL plugin cannot be loaded
std::vector<GlDevice> listGlDevices();

/// A diagnostic: the GL objects alive in the process now, by kind (the GL methods' programs
/// stay cached per worker context; everything else lives for one run). The soak test checks
/// these stay flat over hundreds of runs.
struct GlObjectCounts {
    long buffers = 0;        ///< buffer objects
    long vertex_arrays = 0;  ///< vertex array objects
    long framebuffers = 0;   ///< framebuffer objects
    long programs = 0;       ///< linked programs
    long shaders = 0;        ///< shader objects
    long queries = 0;        ///< query objects (GPU timers)
};
/// The counts of GlObjectCounts; all zero, and nothing loaded, while no GL method has run.
/// Thread-safe.
GlObjectCounts liveGlObjects();

}  // namespace hyvox
