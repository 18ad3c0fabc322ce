// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Headless OpenGL 4.5 core contexts through the EGL device platform
// (EGL_EXT_platform_device): no window system, no X. Displays are never terminated:
// EGL shares a device's display process-wide, and a host (Blender) may be using it.
#include <string>
#include <vector>

namespace hyvox::gl {

struct EglDeviceInfo {
    int index = -1;         // position in eglQueryDevicesEXT's list
    std::string name;       // DRM node or "software"
    bool software = false;  // Mesa's software device (llvmpipe)
};

// Every EGL device of the process, in EGL's order. Empty when EGL has no device platform.
std::vector<EglDeviceInfo> listEglDevices();

// A context made current on the calling thread; only the thread that created it may use
// or destroy it (GlWorker guarantees that).
class EglContext {
public:
    // selection: "" (or "auto") = hardware devices first, then software; "software"; or an
    // index "0", "1", ... into listEglDevices(). Throws BackendError naming the devices found
    // when none gives a GL 4.5 core context.
    explicit EglContext(const std::string& selection);
    ~EglContext();
    EglContext(const EglContext&) = delete;
    EglContext& operator=(const EglContext&) = delete;

    const EglDeviceInfo& device() const { return device_; }
    const std::string& renderer() const { return renderer_; }  // GL_RENDERER
    const std::string& version() const { return version_; }    // GL_VERSION

private:
    void* display_ = nullptr;
    void* context_ = nullptr;
    EglDeviceInfo device_;
    std::string renderer_;
    std::string version_;
};

}  // namespace hyvox::gl
