// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesh_io/obj_materials.h"

#include <cstring>
#include <unordered_map>
#include <vector>

#include "hyvox/errors.h"
#include "mesh_io/mtl_reader.h"
#include "os/file_bytes.h"

namespace hyvox::mesh_io {
namespace {

// Material files are small; a larger one is not a material file.
constexpr std::size_t kMaxMtlBytes = std::size_t(64) << 20;

// "dir/mesh.obj" -> "dir/"; "mesh.obj" -> "".
std::string folderOf(const std::string& path) {
    const std::size_t slash = path.find_last_of('/');
    return slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
}

std::string resolve(const std::string& folder, const std::string& name) {
    return !name.empty() && name.front() == '/' ? name : folder + name;
}

// Why `path` cannot be a material's image, or "" when it is a readable PNG file.
std::string imageProblem(const std::string& path) {
    static const unsigned char kPngSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    try {
        const std::vector<char> head = os::readFilePrefix(path, 8);
        if (head.size() < 8 || std::memcmp(head.data(), kPngSignature, 8) != 0)
            return "is not a PNG (only PNG is read)";
        return "";
    } catch (const InvalidInput&) {
        return "cannot be opened as a file";
    }
}

}  // namespace

void readObjMaterials(Mesh& mesh, const std::string& obj_path) {
    if (!mesh.hasMaterials()) return;
    const std::string folder = folderOf(obj_path);
    struct Found {
        MtlMaterial material;
        std::string folder;  // of its .mtl, for its image
    };
    std::unordered_map<std::string, Found> defined;
    for (const std::string& library : mesh.material_libraries) {
        const std::string path = resolve(folder, library);
        try {
            const std::vector<char> bytes = os::readFileBytes(path, kMaxMtlBytes);
            for (MtlMaterial& m : readMtl(bytes.data(), bytes.size(), path)) {
                std::string name = m.name;
                defined.emplace(std::move(name), Found{std::move(m), folderOf(path)});  // the first definition wins
            }
        } catch (const InvalidInput& error) {
            mesh.warnings.push_back("material file '" + library + "' of '" + obj_path +
                                    "' is not used: " + error.what());
        }
    }
    for (std::size_t m = 0; m < mesh.material_names.size(); ++m) {
        const std::string& name = mesh.material_names[m];
        if (name.empty()) continue;  // faces before any usemtl: the default grey
        const auto it = defined.find(name);
        if (it == defined.end()) {
            mesh.warnings.push_back("material '" + name + "' of '" + obj_path +
                                    "' is in none of its material files: its faces are grey (0.8)");
            continue;
        }
        const MtlMaterial& found = it->second.material;
        if (found.diffuse)
            for (std::size_t c = 0; c < 3; ++c) mesh.material_colors[3 * m + c] = (*found.diffuse)[c];
        if (found.diffuse_map.empty()) continue;
        const std::string image = resolve(it->second.folder, found.diffuse_map);
        const std::string problem = imageProblem(image);
        if (problem.empty())
            mesh.material_textures[m] = image;
        else
            mesh.warnings.push_back("the image '" + image + "' of material '" + name + "' " + problem +
                                    ": its faces take the material's Kd colour instead");
    }
}

}  // namespace hyvox::mesh_io
