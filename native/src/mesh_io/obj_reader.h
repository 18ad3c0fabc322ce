// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A strict Wavefront OBJ reader: positions ("v x y z", optionally "r g b" after them), texture
// coordinates ("vt u v") and faces ("f" with 1-based or negative indices, "v", "v/vt",
// "v//vn", "v/vt/vn"), and the material of each face ("usemtl NAME"; "mtllib" files are
// listed for readMesh, which reads them: obj_materials.h). Everything else (normals, groups,
// lines, points) is skipped. A malformed number, a face with fewer than 3 corners or an index that names no
// vertex defined before it is an InvalidInput naming the file and the line.
#include <cstddef>
#include <string>

#include "hyvox/mesh_io.h"

namespace hyvox::mesh_io {

// Reads the OBJ held in [data, data + size); `name` is quoted in errors. A mesh vertex is
// one distinct (position, texture coordinate) pair the faces use, numbered in the order the
// faces first use it; faces are fan-triangulated in linear time.
Mesh readObj(const char* data, std::size_t size, const std::string& name, Interrupter* interrupter = nullptr);

}  // namespace hyvox::mesh_io
