// SPDX-License-Identifier: GPL-3.0-or-later
// Mesh files through assimp, inside the assimp reader process. Only aiProcess_Triangulate is
// requested: the cleaning steps
// (JoinIdenticalVertices, FindDegenerates, SortByPType + removal, ...) would drop or merge
// triangles, and the voxelizer must see the file's triangles as they are (validate() skips
// and counts degenerate ones itself).
#include "mesh_io/assimp_import.h"

#include <assimp/BaseImporter.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>
#include <assimp/ProgressHandler.hpp>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "hyvox/errors.h"
#include "mesh_io/mesh_formats.h"
#include "mesh_io/weld_vertices.h"

namespace hyvox::mesh_io {
namespace {

struct Appender {
    Mesh& out;
    bool want_colors;
    bool want_uvs;

    void append(const aiMesh& mesh, const aiMatrix4x4& transform) {
        if (!(mesh.mPrimitiveTypes & (aiPrimitiveType_TRIANGLE | aiPrimitiveType_POLYGON))) return;
        const std::size_t base = out.vertexCount();
        if (base + mesh.mNumVertices > std::numeric_limits<std::uint32_t>::max())
            throw InvalidInput("the mesh has too many vertices for 32-bit indices");
        const bool identity = transform.IsIdentity();
        for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
            const aiVector3D p = identity ? mesh.mVertices[v] : transform * mesh.mVertices[v];
            out.positions.insert(out.positions.end(), {p.x, p.y, p.z});
            if (want_colors) {
                const aiColor4D c = mesh.HasVertexColors(0) ? mesh.mColors[0][v] : aiColor4D(1, 1, 1, 1);
                out.colors.insert(out.colors.end(), {c.r, c.g, c.b, c.a});
            }
            if (want_uvs) {
                const aiVector3D t = mesh.HasTextureCoords(0) ? mesh.mTextureCoords[0][v] : aiVector3D(0, 0, 0);
                out.uvs.insert(out.uvs.end(), {t.x, t.y});
            }
        }
        for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
            const aiFace& face = mesh.mFaces[f];
            if (face.mNumIndices != 3) continue;  // points and lines: nothing to voxelize
            for (int c = 0; c < 3; ++c) out.triangles.push_back(std::uint32_t(base + face.mIndices[c]));
        }
    }

    void walk(const aiScene& scene, const aiNode& node, const aiMatrix4x4& parent, std::vector<bool>& seen) {
        const aiMatrix4x4 transform = parent * node.mTransformation;
        for (unsigned m = 0; m < node.mNumMeshes; ++m) {
            const unsigned index = node.mMeshes[m];
            if (index >= scene.mNumMeshes) continue;
            seen[index] = true;
            append(*scene.mMeshes[index], transform);
        }
        for (unsigned c = 0; c < node.mNumChildren; ++c) walk(scene, *node.mChildren[c], transform, seen);
    }
};

// The importer with only the loaders of the formats offered through assimp, so that no file,
// whatever its name or content, reaches another (fewer parsers, fewer ways to fail).
// UnregisterLoader hands each loader back to us to delete.
void keepOfferedFormats(Assimp::Importer& importer) {
    std::vector<Assimp::BaseImporter*> others;
    for (std::size_t n = 0; n < importer.GetImporterCount(); ++n) {
        Assimp::BaseImporter* loader = importer.GetImporter(n);
        std::set<std::string> extensions;
        loader->GetExtensionList(extensions);
        const bool offered = std::any_of(extensions.begin(), extensions.end(), [](const std::string& e) {
            const MeshFormat* format = meshFormat(e);
            return format && readByAssimp(format->reader);
        });
        if (!offered) others.push_back(loader);
    }
    for (Assimp::BaseImporter* loader : others) {
        importer.UnregisterLoader(loader);
        delete loader;
    }
}

Mesh toMesh(const aiScene* scene, Assimp::Importer& importer, const std::string& path, const std::string& extension) {
    if (!scene) throw InvalidInput("cannot read mesh file '" + path + "': " + importer.GetErrorString());
    Mesh mesh;
    Appender appender{mesh, false, false};
    for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
        appender.want_colors |= scene->mMeshes[m]->HasVertexColors(0);
        appender.want_uvs |= scene->mMeshes[m]->HasTextureCoords(0);
    }
    std::vector<bool> seen(scene->mNumMeshes, false);
    if (scene->mRootNode) appender.walk(*scene, *scene->mRootNode, aiMatrix4x4(), seen);
    for (unsigned m = 0; m < scene->mNumMeshes; ++m)
        if (!seen[m]) appender.append(*scene->mMeshes[m], aiMatrix4x4());

    if (mesh.triangleCount() == 0) throw InvalidInput("mesh file '" + path + "' contains no triangles");
    weldIdenticalVertices(mesh);
    return mesh;
}

// assimp asks its progress handler at its own steps; returning false makes the read stop
// and return no scene, which readWithAssimp then reports as hyvox::Cancelled.
class InterruptingProgress final : public Assimp::ProgressHandler {
public:
    explicit InterruptingProgress(Interrupter* interrupter) : interrupter_(interrupter) {}
    bool Update(float) override {
        stopped_ = stopped_ || (interrupter_ && interrupter_->wasInterrupted(-1));
        return !stopped_;
    }
    bool stopped() const { return stopped_; }

private:
    Interrupter* interrupter_;
    bool stopped_ = false;
};

// The importer owns (and deletes) the handler it is given.
InterruptingProgress& watch(Assimp::Importer& importer, Interrupter* interrupter) {
    auto* progress = new InterruptingProgress(interrupter);
    importer.SetProgressHandler(progress);
    return *progress;
}

Mesh finish(const aiScene* scene, Assimp::Importer& importer, const InterruptingProgress& progress,
            const std::string& path, const std::string& extension, Interrupter* interrupter) {
    if (progress.stopped()) throw Cancelled();
    throwIfInterrupted(interrupter);
    return toMesh(scene, importer, path, extension);
}

}  // namespace

Mesh importWithAssimp(const std::string& path, const std::string& extension, Interrupter* interrupter) {
    Assimp::Importer importer;
    keepOfferedFormats(importer);
    const InterruptingProgress& progress = watch(importer, interrupter);
    const aiScene* scene = importer.ReadFile(path, aiProcess_Triangulate);
    return finish(scene, importer, progress, path, extension, interrupter);
}

Mesh importWithAssimp(const char* data, std::size_t size, const std::string& extension, const std::string& path,
                      Interrupter* interrupter) {
    Assimp::Importer importer;
    keepOfferedFormats(importer);
    const InterruptingProgress& progress = watch(importer, interrupter);
    const aiScene* scene = importer.ReadFileFromMemory(data, size, aiProcess_Triangulate, extension.c_str());
    return finish(scene, importer, progress, path, extension, interrupter);
}

}  // namespace hyvox::mesh_io
