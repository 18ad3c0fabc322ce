// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A strict glTF 2.0 reader: .gltf (JSON, its buffers as base64 data: URIs or as files beside
// it) and .glb (the binary container: JSON and one buffer), told apart by their first bytes.
// The mesh is the scene's (the default scene, or every root node when the file has none):
// every node's mesh, its primitives' triangles (triangles, strips and fans; points and lines
// skipped) in world space through the node transforms, with COLOR_0 (linear in glTF, stored
// sRGB-encoded as every mesh here) and TEXCOORD_0 (v flipped to the bottom-left origin the
// other readers use) when present. Materials are not read.
//
// Every reference (buffer, view, accessor, node, mesh) is checked against what it names,
// every accessor against the bytes of its view before anything is read, every index against
// its primitive's vertices; a node reached twice (a cycle, or two parents) and scene
// instances past `max_bytes` are refused. Draco and meshopt compression and sparse
// accessors are refused by name. Any problem is an InvalidInput naming the file and the
// object ("glTF accessors[3]: ..."), never a crash, a hang or a partial mesh.
#include <cstddef>
#include <cstdint>
#include <string>

#include "hyvox/mesh_io.h"

namespace hyvox::mesh_io {

// Reads the glTF held in [data, data + size). `name` is the file's path: quoted in errors,
// and the folder external buffers are read from. `max_bytes` bounds the mesh made (a small
// file can instance a large mesh many times).
Mesh readGltf(const char* data, std::size_t size, const std::string& name, std::uint64_t max_bytes,
              Interrupter* interrupter = nullptr);

}  // namespace hyvox::mesh_io
