// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Test-only reader for the shared meshes' one format (../shared/data/meshes/README.md):
// binary little-endian PLY, vertex = float x,y,z + optional float/uchar extras, faces =
// uchar 3 + 3 int32, optionally gzip-compressed. Independent of native/src/mesh_io on purpose.
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

// The shared meshes every mesh suite runs on, sorted by name: the one list, fixed in code so
// the suites register the same cases whether or not the folder can be read. A test compares it
// with listMeshFiles() (CpuVsReference.MeshListIsComplete), so no mesh is added or removed
// without the suites noticing.
const std::vector<std::string>& sharedMeshFiles();

// A GoogleTest case name for `file` at `resolution`: the name up to its first '.', then
// "_<resolution>", with every non-alphanumeric character as '_' ("spot_uv.ply", 64 ->
// "spot_uv_64").
std::string meshCaseName(const std::string& file, int resolution);

}  // namespace hyvox::test
