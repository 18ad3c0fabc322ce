// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A strict STL reader, binary and ASCII. Binary: an 80-byte header, a 32-bit triangle count
// and 50 bytes a triangle; the file's size must be exactly what the count says (a file cut
// short or with a wrong count is an error, not a shorter mesh). ASCII: "solid", facets of
// "facet normal n n n / outer loop / vertex x y z (three times) / endloop / endfacet", and
// "endsolid" (several solids one after the other are one mesh); every keyword and number is
// checked, and the text must end with "endsolid". Facet normals and the binary attribute
// bytes are not used. Corners at bitwise equal positions are welded into one vertex
// (weld_vertices.h), so the mesh has the vertices a PLY of it would have.
#include <cstddef>
#include <string>

#include "hyvox/mesh_io.h"

namespace hyvox::mesh_io {

// Reads the STL held in [data, data + size); `name` is quoted in errors. Binary unless the
// bytes start with "solid" and are text, as the ASCII form is.
Mesh readStl(const char* data, std::size_t size, const std::string& name, Interrupter* interrupter = nullptr);

}  // namespace hyvox::mesh_io
