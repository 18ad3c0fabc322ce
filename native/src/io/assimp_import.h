// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// What the plugin libhyvox_assimp.so (assimp_import.cpp) offers the reader that loads it
// (assimp_reader.cpp): its entry point hyvox_assimp_import() returns this table. Both are
// built from the same sources in one build (the plugin is found beside the binary that
// loads it), so the types they pass are the same.
#include <cstddef>
#include <string>

#include "core/plugin_library.h"
#include "hyvox/mesh_io.h"

namespace hyvox::io {

struct AssimpImport {
    Mesh (*file)(const std::string& path, const std::string& extension, Interrupter* interrupter);
    Mesh (*bytes)(const char* data, std::size_t size, const std::string& extension, const std::string& path,
                  Interrupter* interrupter);
};

}  // namespace hyvox::io

extern "C" HYVOX_PLUGIN_ENTRY const hyvox::io::AssimpImport* hyvox_assimp_import();
