// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The colours of an OBJ file's materials: its "mtllib" files, found beside it, give each
// "usemtl" name a diffuse colour (Kd) and image (map_Kd, found beside its .mtl).
#include <string>

#include "hyvox/mesh_io.h"

namespace hyvox::mesh_io {

// Fills mesh.material_colors and mesh.material_textures for the names readObj collected,
// reading the material files relative to the folder of `obj_path`. What cannot be used is
// left at the defaults (0.8 grey, no image) with a line in mesh.warnings: a material file
// that is missing or malformed, a material none of them defines, an image that is missing or
// not a PNG (the material then keeps its Kd; Blender's importer also shows the Kd then).
void readObjMaterials(Mesh& mesh, const std::string& obj_path);

}  // namespace hyvox::mesh_io
