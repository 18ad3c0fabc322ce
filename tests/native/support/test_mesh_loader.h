// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Test-only reader for the shared meshes' one format (../shared/data/meshes/README.md):
// binary little-endian PLY, vertex = float x,y,z + optional float/uchar extras, faces =
// uchar 3 + 3 int32, optionally gzip-compressed. Independent of native/src/io on purpose.
#include <cstdint>
#include <string>
#include <vector>

#include "hyvox/mesh.h"
#include "support/mesh_arrays.h"

namespace hyvox::test {

struct TestMesh {
    std::string name;
    std::vector<float> positions;
    std::vector<std::uint32_t> triangles;
    MeshView view() const { return viewOf(positions, triangles); }
};

// Throws std::runtime_error on anything unexpected.
TestMesh loadTestMesh(const std::string& path);

// $HYVOX_MESH_DIR (set by CTest), or "" if unset.
std::string meshDir();
// Every *.ply / *.ply.gz in meshDir(), sorted by name.
std::vector<std::string> listMeshFiles();
// meshDir() + "/" + file.
std::string meshPath(const std::string& file);

}  // namespace hyvox::test
