// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesh_io/mesh_formats.h"

namespace hyvox::mesh_io {

const std::vector<MeshFormat>& meshFormats() {
    static const std::vector<MeshFormat> formats{
        {"ply", MeshReader::Ply, "PLY"},          {"obj", MeshReader::Obj, "Wavefront OBJ"},
        {"stl", MeshReader::Stl, "STL"},          {"off", MeshReader::Off, "OFF"},
        {"gltf", MeshReader::Gltf, "glTF 2.0"},   {"glb", MeshReader::Gltf, "glTF 2.0 binary"},
        {"fbx", MeshReader::Fbx, "FBX (binary)"}, {"3mf", MeshReader::Assimp, "3MF"},
    };
    return formats;
}

const MeshFormat* meshFormat(const std::string& extension) {
    for (const MeshFormat& format : meshFormats())
        if (extension == format.extension) return &format;
    return nullptr;
}

std::string offeredExtensions() {
    std::string text;
    for (const MeshFormat& format : meshFormats()) text += (text.empty() ? "." : ", .") + std::string(format.extension);
    return text;
}

}  // namespace hyvox::mesh_io
