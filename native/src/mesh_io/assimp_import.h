// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Mesh files through assimp: the code of the assimp reader process (assimp_reader_process.cpp),
// the only program that links libassimp. hyvox itself never calls assimp: it starts that
// process (assimp_reader.h), so whatever assimp does on a damaged file ends that process only.
#include <cstddef>
#include <string>

#include "hyvox/mesh_io.h"

namespace hyvox::mesh_io {

// Reads `path` as the format `extension` names ("gltf", ...: mesh_formats.h). Only the
// importers of the formats offered through assimp are registered, so no file, whatever its
// name or content, reaches another. `progress` (may be null) is told assimp's progress
// steps. Throws InvalidInput when assimp cannot read the file or it holds no triangles.
Mesh importWithAssimp(const std::string& path, const std::string& extension, Interrupter* progress);

// The same for bytes in memory (a gzipped file, decompressed); `path` is quoted in errors.
Mesh importWithAssimp(const char* data, std::size_t size, const std::string& extension, const std::string& path,
                      Interrupter* progress);

}  // namespace hyvox::mesh_io
