// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The GL methods (triangle, fragment, hybrid, tessellation) live in the plugin
// libhyvox_gl_methods.so (src/gl_methods/), the only part of hyvox that links libepoxy and
// libEGL: it is loaded the first time a GL method runs or the GL devices are asked for, so
// a cpu run never loads the GL stack (core/plugin_library.h). Its entry point returns the
// table of its entries, which report what they throw as a PluginFault (core/plugin_fault.h);
// the dispatcher (src/voxelize/) calls them through GlMethods, which throws it again.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/backends.h"
#include "core/plugin_fault.h"
#include "core/plugin_library.h"
#include "hyvox/gl_devices.h"

namespace hyvox {

// The plugin's entries (each reports what it throws in its last argument).
struct GlMethodsTable {
    void (*run_hybrid)(const BackendJob& job, TileOutput& out, Stats& stats, PluginFault& fault);
    void (*run_tessellation)(const BackendJob& job, TileOutput& out, Stats& stats, PluginFault& fault);
    std::uint64_t (*tessellation_tile_bytes)(const std::string& device, std::uint64_t budget, int channels,
                                             PluginFault& fault);
    std::vector<GlDevice> (*list_devices)(PluginFault& fault);
    GlObjectCounts (*object_counts)(PluginFault& fault);
};

// The host's view of the plugin: each call throws the plugin's fault as the host's exception.
class GlMethods {
public:
    GlMethods(const GlMethodsTable& table, std::string purpose) : table_(table), purpose_(std::move(purpose)) {}
    void run_hybrid(const BackendJob& job, TileOutput& out, Stats& stats) const;        // triangle|fragment|hybrid
    void run_tessellation(const BackendJob& job, TileOutput& out, Stats& stats) const;  // tessellation
    // The tessellation's largest tile, in bytes of its bits, on `device`: one shader storage
    // block (GL_MAX_SHADER_STORAGE_BLOCK_SIZE: it holds a tile's bits in one); with `channels`
    // attribute channels, small enough that every brick's count block and sums fit a storage
    // block and `budget` bytes.
    std::uint64_t tessellation_tile_bytes(const std::string& device, std::uint64_t budget, int channels) const;
    std::vector<GlDevice> list_devices() const;
    GlObjectCounts object_counts() const;  // the GL objects alive in the plugin, by kind

private:
    const GlMethodsTable& table_;
    std::string purpose_;
};

// The plugin's entries, loading it on first use; BackendError naming the plugin (and why it
// did not load) when it cannot be loaded; `purpose` says what needed it ("the hybrid method").
GlMethods glMethods(const std::string& purpose);

}  // namespace hyvox

extern "C" HYVOX_PLUGIN_ENTRY const hyvox::GlMethodsTable* hyvox_gl_methods();
