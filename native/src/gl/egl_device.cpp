// SPDX-License-Identifier: GPL-3.0-or-later
#include "gl/egl_device.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <cstring>

#include "hyvox/errors.h"

namespace hyvox::gl {
namespace {

std::vector<EGLDeviceEXT> queryDevices() {
    if (!epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_device_enumeration") &&
        !epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_device_base"))
        return {};
    if (!epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_platform_device")) return {};
    EGLint count = 0;
    if (!eglQueryDevicesEXT(0, nullptr, &count) || count <= 0) return {};
    std::vector<EGLDeviceEXT> devices(static_cast<std::size_t>(count));
    if (!eglQueryDevicesEXT(count, devices.data(), &count)) return {};
    devices.resize(static_cast<std::size_t>(count));
    return devices;
}

bool hasToken(const char* list, const char* token) {
    if (!list) return false;
    const std::size_t n = std::strlen(token);
    for (const char* p = list; (p = std::strstr(p, token)) != nullptr; p += n)
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
    return false;
}

EglDeviceInfo describe(EGLDeviceEXT device, int index) {
    EglDeviceInfo info;
    info.index = index;
    const char* extensions = eglQueryDeviceStringEXT(device, EGL_EXTENSIONS);
    info.software = hasToken(extensions, "EGL_MESA_device_software");
    if (hasToken(extensions, "EGL_EXT_device_drm")) {
        const char* node = eglQueryDeviceStringEXT(device, EGL_DRM_DEVICE_FILE_EXT);
        if (node) info.name = node;
    }
    if (info.name.empty()) info.name = info.software ? "software" : "unnamed";
    return info;
}

std::string deviceList(const std::vector<EglDeviceInfo>& devices) {
    if (devices.empty()) return "no EGL devices (is EGL_EXT_platform_device available?)";
    std::string text;
    for (const auto& d : devices)
        text += (text.empty() ? "" : ", ") + std::to_string(d.index) + ": " + d.name +
            (d.software ? " (software)" : " (hardware)");
    return text;
}

// Tries one device; returns false with a reason instead of throwing so the caller can move on.
bool tryCreate(EGLDeviceEXT device, EGLDisplay& display, EGLContext& context, std::string& why) {
    display = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, device, nullptr);
    EGLint major = 0, minor = 0;
    if (display == EGL_NO_DISPLAY || !eglInitialize(display, &major, &minor)) {
        why = "eglInitialize failed";
        return false;
    }
    if (!epoxy_has_egl_extension(display, "EGL_KHR_surfaceless_context")) {
        why = "no EGL_KHR_surfaceless_context";
        return false;
    }
    if (!eglBindAPI(EGL_OPENGL_API)) {
        why = "no desktop OpenGL API";
        return false;
    }
    EGLConfig config = EGL_NO_CONFIG_KHR;
    if (!epoxy_has_egl_extension(display, "EGL_KHR_no_config_context")) {
        const EGLint attributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_NONE};
        EGLint found = 0;
        if (!eglChooseConfig(display, attributes, &config, 1, &found) || found < 1) {
            why = "no OpenGL config";
            return false;
        }
    }
    const EGLint context_attributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                         4,
                                         EGL_CONTEXT_MINOR_VERSION,
                                         5,
                                         EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                         EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                         EGL_CONTEXT_OPENGL_DEBUG,
                                         EGL_TRUE,
                                         EGL_NONE};
    context = eglCreateContext(display, config, EGL_NO_CONTEXT, context_attributes);
    if (context == EGL_NO_CONTEXT) {
        why = "no OpenGL 4.5 core context (EGL error " + std::to_string(eglGetError()) + ")";
        return false;
    }
    if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
        eglDestroyContext(display, context);
        context = EGL_NO_CONTEXT;
        why = "eglMakeCurrent (surfaceless) failed";
        return false;
    }
    return true;
}

}  // namespace

std::vector<EglDeviceInfo> listEglDevices() {
    std::vector<EglDeviceInfo> out;
    const auto devices = queryDevices();
    for (std::size_t i = 0; i < devices.size(); ++i) out.push_back(describe(devices[i], int(i)));
    return out;
}

EglContext::EglContext(const std::string& selection) {
    const auto devices = queryDevices();
    std::vector<EglDeviceInfo> infos;
    for (std::size_t i = 0; i < devices.size(); ++i) infos.push_back(describe(devices[i], int(i)));

    // The order to try: an explicit index alone; otherwise hardware first, then software.
    std::vector<int> order;
    if (selection.empty() || selection == "auto" || selection == "software") {
        for (const auto& d : infos)
            if (!d.software && selection != "software") order.push_back(d.index);
        for (const auto& d : infos)
            if (d.software) order.push_back(d.index);
    } else {
        char* end = nullptr;
        const long index = std::strtol(selection.c_str(), &end, 10);
        if (end == selection.c_str() || *end != '\0' || index < 0 || index >= long(infos.size()))
            throw BackendError(
                "GL device '" + selection +
                "' does not exist (choose auto, software or an index); EGL devices: " + deviceList(infos));
        order.push_back(int(index));
    }

    std::string reasons;
    for (int index : order) {
        EGLDisplay display = EGL_NO_DISPLAY;
        EGLContext context = EGL_NO_CONTEXT;
        std::string why;
        if (tryCreate(devices[std::size_t(index)], display, context, why)) {
            display_ = display;
            context_ = context;
            device_ = infos[std::size_t(index)];
            const auto text = [](GLenum name) {
                const auto* s = reinterpret_cast<const char*>(glGetString(name));
                return std::string(s ? s : "?");
            };
            renderer_ = text(GL_RENDERER);
            version_ = text(GL_VERSION);
            if (epoxy_gl_version() < 45) {
                eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
                eglDestroyContext(display, context);
                context_ = nullptr;
                reasons += "; " + std::to_string(index) + ": GL " + version_ + " is older than 4.5";
                continue;
            }
            return;
        }
        reasons += "; " + std::to_string(index) + ": " + why;
    }
    throw BackendError("no EGL device offers an OpenGL 4.5 core context (selection '" +
                       (selection.empty() ? std::string("auto") : selection) + "'); EGL devices: " + deviceList(infos) +
                       reasons);
}

EglContext::~EglContext() {
    if (!context_) return;
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display_, context_);
    eglReleaseThread();
    // No eglTerminate: the device display is shared by everything in the process.
}

}  // namespace hyvox::gl
