// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A strict PLY reader (ascii, binary_little_endian, binary_big_endian). Every count the header
// declares is checked against the bytes that follow before anything is allocated for it;
// a short, malformed or inconsistent file is an InvalidInput naming the file and the place
// (header line, body line, or element number), never a crash, a hang or a partial mesh.
#include <cstddef>
#include <string>

#include "hyvox/mesh_io.h"

namespace hyvox::mesh_io {

// Reads the PLY held in [data, data + size). `name` (the file's path) is quoted in errors.
// Vertices come from the element "vertex" (x, y, z required; red/green/blue[/alpha] become
// colours, integer channels scaled to 0..1; u/v, s/t or texture_u/texture_v become UVs),
// faces from the list "vertex_indices" (or "vertex_index") of the element "face",
// fan-triangulated. Other elements and properties are skipped.
Mesh readPly(const char* data, std::size_t size, const std::string& name, Interrupter* interrupter = nullptr);

// Whether the bytes start like a PLY file ("ply" and a line end), whatever the file's name.
bool looksLikePly(const char* data, std::size_t size);

}  // namespace hyvox::mesh_io
