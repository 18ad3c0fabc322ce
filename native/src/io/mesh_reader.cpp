// SPDX-License-Identifier: GPL-3.0-or-later
// Mesh files through assimp. Only aiProcess_Triangulate is requested: the cleaning steps
// (JoinIdenticalVertices, FindDegenerates, SortByPType + removal, ...) would drop or merge
// triangles, and the voxelizer must see the file's triangles as they are (validate() skips
// and counts degenerate ones itself).
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <sys/stat.h>
#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <limits>
#include <string>
#include <unordered_map>
#include <vector>

#include "hyvox/errors.h"
#include "hyvox/mesh_io.h"

namespace hyvox {
namespace {

std::string lower(std::string text) {
    std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return text;
}

bool endsWith(const std::string& text, const std::string& suffix) {
    return text.size() >= suffix.size() && text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// The extension assimp should parse "name.ext.gz" as: "ext".
std::string innerExtension(const std::string& lower_path) {
    const std::string stem = lower_path.substr(0, lower_path.size() - 3);
    const auto dot = stem.find_last_of('.');
    const auto slash = stem.find_last_of('/');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
    return stem.substr(dot + 1);
}

std::vector<char> gunzipFile(const std::string& path) {
    gzFile file = gzopen(path.c_str(), "rb");
    if (!file) throw InvalidInput("cannot open mesh file '" + path + "': " + std::strerror(errno));
    std::vector<char> data;
    std::vector<char> chunk(1 << 20);
    for (;;) {
        const int n = gzread(file, chunk.data(), unsigned(chunk.size()));
        if (n < 0) {
            int code = 0;
            const std::string message = gzerror(file, &code);
            gzclose(file);
            throw InvalidInput("cannot decompress mesh file '" + path + "': " + message);
        }
        if (n == 0) break;
        data.insert(data.end(), chunk.data(), chunk.data() + n);
    }
    gzclose(file);
    if (data.empty()) throw InvalidInput("mesh file '" + path + "' is empty after decompression");
    return data;
}

void checkReadable(const std::string& path) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0)
        throw InvalidInput("cannot open mesh file '" + path + "': " + std::strerror(errno));
    if (S_ISDIR(st.st_mode)) throw InvalidInput("mesh path '" + path + "' is a folder, not a file");
    std::ifstream probe(path, std::ios::binary);
    if (!probe) throw InvalidInput("cannot open mesh file '" + path + "': " + std::strerror(errno));
    if (st.st_size == 0) throw InvalidInput("mesh file '" + path + "' is empty");
}

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

// Assimp's OBJ and STL importers give every face corner its own vertex. Welding corners whose
// attributes are bitwise equal restores the file's shared vertices (and vertex count)
// without touching any triangle.
void weldIdenticalVertices(Mesh& mesh) {
    const std::size_t n = mesh.vertexCount();
    const std::size_t colors = mesh.hasColors() ? 4 : 0;
    const std::size_t uvs = mesh.hasUvs() ? 2 : 0;
    struct Key {
        float v[9];
        std::size_t size;
        bool operator==(const Key& o) const { return std::memcmp(v, o.v, size * sizeof(float)) == 0; }
    };
    struct Hash {
        std::size_t operator()(const Key& k) const {
            std::uint64_t h = 1469598103934665603ull;
            const auto* bytes = reinterpret_cast<const unsigned char*>(k.v);
            for (std::size_t b = 0; b < k.size * sizeof(float); ++b) h = (h ^ bytes[b]) * 1099511628211ull;
            return std::size_t(h);
        }
    };
    std::unordered_map<Key, std::uint32_t, Hash> index;
    index.reserve(n);
    std::vector<std::uint32_t> remap(n);
    Mesh out;
    for (std::size_t v = 0; v < n; ++v) {
        Key key{};
        key.size = 3 + colors + uvs;
        std::memcpy(key.v, &mesh.positions[3 * v], 3 * sizeof(float));
        if (colors) std::memcpy(key.v + 3, &mesh.colors[4 * v], 4 * sizeof(float));
        if (uvs) std::memcpy(key.v + 3 + colors, &mesh.uvs[2 * v], 2 * sizeof(float));
        const auto [it, inserted] = index.emplace(key, std::uint32_t(out.vertexCount()));
        if (inserted) {
            out.positions.insert(out.positions.end(), key.v, key.v + 3);
            if (colors) out.colors.insert(out.colors.end(), key.v + 3, key.v + 7);
            if (uvs) out.uvs.insert(out.uvs.end(), key.v + 3 + colors, key.v + 5 + colors);
        }
        remap[v] = it->second;
    }
    out.triangles = std::move(mesh.triangles);
    for (std::uint32_t& t : out.triangles) t = remap[t];
    mesh = std::move(out);
}

}  // namespace

Mesh readMesh(const std::string& path) {
    checkReadable(path);
    const std::string lower_path = lower(path);
    const bool gzipped = endsWith(lower_path, ".gz");
    const auto dot = lower_path.find_last_of('.');
    const std::string extension =
        gzipped ? innerExtension(lower_path) : (dot == std::string::npos ? "" : lower_path.substr(dot + 1));

    Assimp::Importer importer;
    const unsigned flags = aiProcess_Triangulate;
    const aiScene* scene = nullptr;
    if (gzipped) {
        if (extension.empty())
            throw InvalidInput("cannot tell the format of '" + path + "': name it like mesh.ply.gz or mesh.obj.gz");
        const std::vector<char> data = gunzipFile(path);
        scene = importer.ReadFileFromMemory(data.data(), data.size(), flags, extension.c_str());
    } else {
        scene = importer.ReadFile(path, flags);
    }
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
    if (extension == "obj" || extension == "stl") weldIdenticalVertices(mesh);
    return mesh;
}

}  // namespace hyvox
