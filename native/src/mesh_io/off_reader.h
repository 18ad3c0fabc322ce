// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A strict reader of the ASCII Object File Format (OFF, as Geomview and CGAL write it): an
// optional keyword line (OFF, COFF with vertex colours, NOFF / CNOFF with normals, STOFF with
// texture coordinates, and their combinations), the counts "vertices faces [edges]", one
// vertex a line, then one face a line ("n i1 ... in" and an optional face colour, which is
// not used). '#' starts a comment. The vertex and face counts are checked against the bytes
// present before anything is allocated; a line with a value missing or one too many, an
// index that names no vertex, or anything but comments after the last face is an
// InvalidInput naming the file and the line. Binary OFF and other dimensions (4OFF, nOFF)
// are refused by name.
#include <cstddef>
#include <string>

#include "hyvox/mesh_io.h"

namespace hyvox::mesh_io {

Mesh readOff(const char* data, std::size_t size, const std::string& name, Interrupter* interrupter = nullptr);

}  // namespace hyvox::mesh_io
