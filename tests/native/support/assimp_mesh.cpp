// SPDX-License-Identifier: GPL-3.0-or-later
#include "support/assimp_mesh.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <zlib.h>
#include <assimp/Importer.hpp>

#include <stdexcept>
#include <string>
#include <vector>

namespace hyvox::test {
namespace {

std::vector<char> gunzip(const std::string& path) {
    gzFile file = gzopen(path.c_str(), "rb");
    if (!file) throw std::runtime_error("cannot open " + path);
    std::vector<char> data, chunk(1 << 20);
    for (int n; (n = gzread(file, chunk.data(), unsigned(chunk.size()))) > 0;)
        data.insert(data.end(), chunk.data(), chunk.data() + n);
    gzclose(file);
    return data;
}

}  // namespace

Mesh readMeshWithAssimp(const std::string& path) {
    Assimp::Importer importer;
    const aiScene* scene = nullptr;
    const bool gzipped = path.size() > 3 && path.compare(path.size() - 3, 3, ".gz") == 0;
    std::vector<char> data;
    if (gzipped) {
        data = gunzip(path);
        const std::string stem = path.substr(0, path.size() - 3);
        const std::string extension = stem.substr(stem.find_last_of('.') + 1);
        scene = importer.ReadFileFromMemory(data.data(), data.size(), aiProcess_Triangulate, extension.c_str());
    } else {
        scene = importer.ReadFile(path, aiProcess_Triangulate);
    }
    if (!scene) throw std::runtime_error("assimp cannot read " + path + ": " + importer.GetErrorString());
    Mesh out;
    for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
        const aiMesh& mesh = *scene->mMeshes[m];
        const std::uint32_t base = std::uint32_t(out.vertexCount());
        for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
            out.positions.insert(out.positions.end(), {mesh.mVertices[v].x, mesh.mVertices[v].y, mesh.mVertices[v].z});
            if (mesh.HasVertexColors(0)) {
                const aiColor4D c = mesh.mColors[0][v];
                out.colors.insert(out.colors.end(), {c.r, c.g, c.b, c.a});
            }
            if (mesh.HasTextureCoords(0))
                out.uvs.insert(out.uvs.end(), {mesh.mTextureCoords[0][v].x, mesh.mTextureCoords[0][v].y});
        }
        for (unsigned f = 0; f < mesh.mNumFaces; ++f)
            if (mesh.mFaces[f].mNumIndices == 3)
                for (int c = 0; c < 3; ++c) out.triangles.push_back(base + mesh.mFaces[f].mIndices[c]);
    }
    return out;
}

}  // namespace hyvox::test
