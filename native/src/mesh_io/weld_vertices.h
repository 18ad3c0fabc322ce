// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// STL files, and assimp for most formats, give every face corner its own vertex. Welding
// corners whose attributes (position, colour, uv) are bitwise equal restores the shared
// vertices (and the vertex count a PLY of the same mesh has) without touching any triangle.
#include "hyvox/mesh_io.h"

namespace hyvox::mesh_io {

void weldIdenticalVertices(Mesh& mesh);

}  // namespace hyvox::mesh_io
