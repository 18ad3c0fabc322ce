// SPDX-License-Identifier: GPL-3.0-or-later
// The host side of the GL methods' plugin (core/gl_methods.h), and the public GL device
// queries, which go through it.
#include "core/gl_methods.h"

#include "hyvox/gl_devices.h"

namespace hyvox {

const GlMethods& glMethods(const std::string& purpose) {
    using Entry = decltype(&hyvox_gl_methods);
    return *reinterpret_cast<Entry>(pluginSymbol("gl_methods", "hyvox_gl_methods", purpose))();
}

std::vector<GlDevice> listGlDevices() { return glMethods("listing the GL devices").list_devices(); }

GlObjectCounts liveGlObjects() {
    // No GL object can exist before the plugin is loaded: asking must not load it.
    if (!pluginLoaded("gl_methods")) return {};
    return glMethods("counting GL objects").object_counts();
}

}  // namespace hyvox
