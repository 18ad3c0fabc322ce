// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The mesh file formats readMesh offers, by file extension, and which reader reads each:
// hyvox's own strict readers in this process, or assimp in a process of its own
// (assimp_reader.h). A format assimp knows but hyvox does not offer is refused by name,
// and its importer is not registered in the assimp process either (docs/mesh-formats.md
// says why each format is read the way it is).
#include <string>
#include <vector>

namespace hyvox::mesh_io {

// Fbx: the container checked here (fbx_check.h), then read by assimp; Assimp: read by assimp.
enum class MeshReader { Ply, Obj, Stl, Off, Gltf, Fbx, Assimp };

inline bool readByAssimp(MeshReader reader) { return reader == MeshReader::Fbx || reader == MeshReader::Assimp; }

struct MeshFormat {
    const char* extension;  // lower case, without the dot
    MeshReader reader;
    const char* name;  // for messages and the docs
};

const std::vector<MeshFormat>& meshFormats();

// The format of a lower-case extension ("glb"), or null when hyvox does not read it.
const MeshFormat* meshFormat(const std::string& extension);

// ".ply, .obj, ..." for messages.
std::string offeredExtensions();

}  // namespace hyvox::mesh_io
