// SPDX-License-Identifier: GPL-3.0-or-later
// The formats hyvox does not read itself go to assimp, in the plugin libhyvox_assimp.so,
// loaded here on the first such file: a PLY or OBJ run never loads libassimp and the ten
// libraries it brings (core/plugin_library.h).
#include "io/assimp_reader.h"

#include "core/plugin_library.h"
#include "io/assimp_import.h"

namespace hyvox::io {
namespace {

const AssimpImport& assimp(const std::string& path) {
    using Entry = decltype(&hyvox_assimp_import);
    const auto entry = reinterpret_cast<Entry>(pluginSymbol("assimp", "hyvox_assimp_import", "reading '" + path + "'"));
    return *entry();
}

}  // namespace

Mesh readWithAssimp(const std::string& path, const std::string& extension, Interrupter* interrupter) {
    return assimp(path).file(path, extension, interrupter);
}

Mesh readWithAssimp(const char* data, std::size_t size, const std::string& extension, const std::string& path,
                    Interrupter* interrupter) {
    return assimp(path).bytes(data, size, extension, path, interrupter);
}

}  // namespace hyvox::io
