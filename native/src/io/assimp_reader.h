// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The formats hyvox does not read itself (STL, glTF, FBX, ...) through assimp. Its PLY and
// OBJ importers are removed from the importer first: those formats have strict readers of
// their own (ply_reader.h, obj_reader.h), and assimp's crash or hang on damaged files.
#include <cstddef>
#include <string>

#include "hyvox/mesh_io.h"

namespace hyvox::io {

// Reads `path` by its extension (assimp may also recognise the content).
// `interrupter` (may be null) is asked at assimp's progress steps (hyvox::Cancelled).
Mesh readWithAssimp(const std::string& path, const std::string& extension, Interrupter* interrupter = nullptr);

// Reads decompressed bytes as the format `extension` names ("stl", ...).
Mesh readWithAssimp(const char* data, std::size_t size, const std::string& extension, const std::string& path,
                    Interrupter* interrupter = nullptr);

}  // namespace hyvox::io
