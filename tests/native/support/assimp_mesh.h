// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Mesh reading as hyvox::readMesh did it before it had its own PLY and OBJ readers: assimp
// with aiProcess_Triangulate, ".gz" through gzread. The tests compare the new readers with
// it on every shared mesh, and bench_mesh_read times both. It trusts its input: never give
// it a damaged file (that is what the new readers are for).
#include <string>

#include "hyvox/mesh_io.h"

namespace hyvox::test {

// The meshes of the file, in scene order, merged (node transforms are not applied: the
// shared meshes hold one mesh each). Throws std::runtime_error when assimp fails.
Mesh readMeshWithAssimp(const std::string& path);

}  // namespace hyvox::test
