// SPDX-License-Identifier: GPL-3.0-or-later
// The host side of the GL methods' plugin (core/gl_methods.h), and the public GL device
// queries, which go through it.
#include "core/gl_methods.h"

#include "hyvox/gl_devices.h"

namespace hyvox {

GlMethods glMethods(const std::string& purpose) {
    using Entry = decltype(&hyvox_gl_methods);
    return {*reinterpret_cast<Entry>(pluginSymbol("gl_methods", "hyvox_gl_methods", purpose))(), purpose};
}

void GlMethods::run_hybrid(const BackendJob& job, TileOutput& out, Stats& stats) const {
    callPlugin(purpose_, table_.run_hybrid, job, out, stats);
}

void GlMethods::run_tessellation(const BackendJob& job, TileOutput& out, Stats& stats) const {
    callPlugin(purpose_, table_.run_tessellation, job, out, stats);
}

std::uint64_t GlMethods::tessellation_tile_bytes(const std::string& device, std::uint64_t budget, int channels) const {
    return callPlugin(purpose_, table_.tessellation_tile_bytes, device, budget, channels);
}

std::vector<GlDevice> GlMethods::list_devices() const { return callPlugin(purpose_, table_.list_devices); }

GlObjectCounts GlMethods::object_counts() const { return callPlugin(purpose_, table_.object_counts); }

std::vector<GlDevice> listGlDevices() { return glMethods("listing the GL devices").list_devices(); }

GlObjectCounts liveGlObjects() {
    // No GL object can exist before the plugin is loaded: asking must not load it.
    if (!pluginLoaded("gl_methods")) return {};
    return glMethods("counting GL objects").object_counts();
}

}  // namespace hyvox
