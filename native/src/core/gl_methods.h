// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The GL methods (triangle, fragment, hybrid, tessellation) live in the plugin
// libhyvox_gl_methods.so (src/gl_methods/), the only part of hyvox that links libepoxy and
// libEGL: it is loaded the first time a GL method runs or the GL devices are asked for, so
// a cpu run never loads the GL stack (core/plugin_library.h). Its entry point returns this
// table; the dispatcher (src/voxelize/) calls through it.
#include <cstdint>
#include <string>
#include <vector>

#include "core/backends.h"
#include "core/plugin_library.h"
#include "hyvox/gl_devices.h"

namespace hyvox {

struct GlMethods {
    void (*run_hybrid)(const BackendJob& job, TileOutput& out, Stats& stats);        // triangle|fragment|hybrid
    void (*run_tessellation)(const BackendJob& job, TileOutput& out, Stats& stats);  // tessellation
    // The tessellation's largest tile, in bytes of its bits, on `device`: one shader storage
    // block (GL_MAX_SHADER_STORAGE_BLOCK_SIZE: it holds a tile's bits in one); with `channels`
    // attribute channels, small enough that every brick's count block and sums fit a storage
    // block and `budget` bytes.
    std::uint64_t (*tessellation_tile_bytes)(const std::string& device, std::uint64_t budget, int channels);
    std::vector<GlDevice> (*list_devices)();
    GlObjectCounts (*object_counts)();  // the GL objects alive in the plugin, by kind
};

// The plugin's table, loading it on first use; BackendError naming the plugin (and why it
// did not load) when it cannot be loaded; `purpose` says what needed it ("the hybrid method").
const GlMethods& glMethods(const std::string& purpose);

}  // namespace hyvox

extern "C" HYVOX_PLUGIN_ENTRY const hyvox::GlMethods* hyvox_gl_methods();
