// SPDX-License-Identifier: GPL-3.0-or-later
// OBJ is read line by line in one pass. Indices are resolved as they are read (negative ones
// count back from the vertices defined so far), so every error can name its line.
#include "mesh_io/obj_reader.h"

#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "mesh_io/text_scanner.h"
#include "os/mesh_file_error.h"

namespace hyvox::mesh_io {
namespace {

constexpr std::uint32_t kNoUv = std::numeric_limits<std::uint32_t>::max();
constexpr std::uint32_t kNoMaterial = std::numeric_limits<std::uint32_t>::max();

class ObjParser {
public:
    ObjParser(const char* data, std::size_t size, const std::string& name, Interrupter* interrupter)
        : scanner_(data, data + size), name_(name), interrupter_(interrupter) {}

    Mesh parse() {
        std::uint64_t line = 0;
        do {
            if ((line++ & 0xFFFF) == 0) throwIfInterrupted(interrupter_);  // between chunks of 64k lines
            std::string_view keyword;
            if (!scanner_.wordOnLine(keyword)) continue;
            if (keyword == "v")
                readPosition();
            else if (keyword == "vt")
                readUv();
            else if (keyword == "f")
                readFace();
            else if (keyword == "usemtl")
                useMaterial();
            else if (keyword == "mtllib")
                addLibraries();
            // Anything else (#, vn, g, o, s, l, p, ...) holds nothing to voxelize.
        } while (scanner_.nextLine());
        if (mesh_.triangles.empty())
            os::failMeshFile(name_, "contains no triangles (no 'f' line with 3 or more corners)");
        if (any_material_) {
            mesh_.material_colors.assign(3 * mesh_.material_names.size(), 0.8f);
            mesh_.material_textures.assign(mesh_.material_names.size(), "");
        } else {
            mesh_.material_ids.clear();
            mesh_.material_names.clear();
        }
        if (!any_uv_) mesh_.uvs.clear();
        if (!any_color_) mesh_.colors.clear();
        return std::move(mesh_);
    }

private:
    [[noreturn]] void fail(const std::string& what) const {
        os::failMeshFile(name_, "line " + std::to_string(scanner_.line()) + ": " + what);
    }

    float number(std::string_view word) const {
        float value = 0;
        if (!parseNumber(word, value)) fail(quoteWord(word) + " is not a number");
        return value;
    }

    void readPosition() {
        float values[7];
        int n = 0;
        std::string_view word;
        while (scanner_.wordOnLine(word)) {
            if (n == 7) fail("a 'v' line has 3 coordinates (and optionally w, or r g b), this one more than 7");
            values[n++] = number(word);
        }
        if (n != 3 && n != 4 && n != 6)
            fail("a 'v' line has x y z (and optionally w, or r g b), this one has " + std::to_string(n) + " numbers");
        file_positions_.insert(file_positions_.end(), values, values + 3);
        if (n == 6) {
            any_color_ = true;
            file_colors_.insert(file_colors_.end(), {values[3], values[4], values[5]});
        } else {
            file_colors_.insert(file_colors_.end(), {1.0f, 1.0f, 1.0f});
        }
    }

    void readUv() {
        float values[3] = {0, 0, 0};
        int n = 0;
        std::string_view word;
        while (scanner_.wordOnLine(word)) {
            if (n == 3) fail("a 'vt' line has at most 3 numbers");
            values[n++] = number(word);
        }
        if (n == 0) fail("a 'vt' line needs at least u");
        file_uvs_.insert(file_uvs_.end(), {values[0], values[1]});
    }

    // "7", "-1": a position in a list of `count` entries defined so far, 0-based.
    std::uint32_t resolve(std::string_view text, std::size_t count, const char* what) const {
        std::int64_t i = 0;
        if (!parseNumber(text, i)) fail(quoteWord(text) + " is not a " + std::string(what) + " index");
        const std::int64_t resolved = i > 0 ? i - 1 : std::int64_t(count) + i;
        if (i == 0 || resolved < 0 || resolved >= std::int64_t(count))
            fail(std::string(what) + " index " + std::to_string(i) + " names none of the " + std::to_string(count) +
                 " " + what + "s defined before this line");
        return std::uint32_t(resolved);
    }

    // The mesh vertex of one face corner "v[/vt[/vn]]", made on its first use.
    std::uint32_t corner(std::string_view text) {
        const std::size_t slash = text.find('/');
        const std::uint32_t v = resolve(text.substr(0, slash), file_positions_.size() / 3, "vertex");
        std::uint32_t vt = kNoUv;
        if (slash != std::string_view::npos) {
            const std::string_view rest = text.substr(slash + 1);
            const std::string_view uv = rest.substr(0, rest.find('/'));
            if (!uv.empty()) vt = resolve(uv, file_uvs_.size() / 2, "texture coordinate");
            // The normal index (after the second slash) is not used.
        }
        const std::uint64_t key = (std::uint64_t(v) << 32) | vt;
        const auto [it, inserted] = vertex_of_corner_.emplace(key, std::uint32_t(mesh_.vertexCount()));
        if (inserted) {
            if (mesh_.vertexCount() >= std::numeric_limits<std::uint32_t>::max())
                fail("more distinct face corners than 32-bit indices can number");
            mesh_.positions.insert(mesh_.positions.end(), &file_positions_[3 * v], &file_positions_[3 * v] + 3);
            const float* c = &file_colors_[3 * v];
            mesh_.colors.insert(mesh_.colors.end(), {c[0], c[1], c[2], 1.0f});
            any_uv_ |= vt != kNoUv;
            if (vt != kNoUv)
                mesh_.uvs.insert(mesh_.uvs.end(), {file_uvs_[2 * vt], file_uvs_[2 * vt + 1]});
            else
                mesh_.uvs.insert(mesh_.uvs.end(), {0.0f, 0.0f});
        }
        return it->second;
    }

    // "usemtl NAME": the faces after it take the material NAME (numbered by first use).
    void useMaterial() {
        std::string_view first, word;
        if (!scanner_.wordOnLine(first)) fail("'usemtl' needs a material name");
        const char* end = first.data() + first.size();
        while (scanner_.wordOnLine(word)) end = word.data() + word.size();
        const std::string name(first.data(), std::size_t(end - first.data()));
        any_material_ = true;
        material_ = materialNamed(name);
    }

    std::uint32_t materialNamed(const std::string& name) {
        const auto [it, inserted] = material_of_name_.emplace(name, std::uint32_t(mesh_.material_names.size()));
        if (inserted) mesh_.material_names.push_back(name);
        return it->second;
    }

    // "mtllib A.mtl [B.mtl ...]": the material files, read by readMesh beside the OBJ.
    void addLibraries() {
        std::string_view word;
        while (scanner_.wordOnLine(word)) mesh_.material_libraries.emplace_back(word);
    }

    // Fan-triangulated as the corners are read: (0,1,2), (0,2,3), ... in one pass.
    void readFace() {
        std::string_view word;
        std::uint32_t first = 0, previous = 0;
        std::size_t n = 0;
        while (scanner_.wordOnLine(word)) {
            const std::uint32_t current = corner(word);
            if (n == 0)
                first = current;
            else if (n >= 2) {
                mesh_.triangles.insert(mesh_.triangles.end(), {first, previous, current});
                if (material_ == kNoMaterial) material_ = materialNamed("");
                mesh_.material_ids.push_back(material_);
            }
            previous = current;
            ++n;
        }
        if (n < 3) fail("a face needs at least 3 corners, this one has " + std::to_string(n));
    }

    TextScanner scanner_;
    const std::string& name_;
    Interrupter* interrupter_;
    std::vector<float> file_positions_, file_colors_, file_uvs_;
    std::unordered_map<std::uint64_t, std::uint32_t> vertex_of_corner_;
    bool any_uv_ = false, any_color_ = false, any_material_ = false;
    // Faces before any usemtl: material "" (named on first use, when the file has materials).
    std::unordered_map<std::string, std::uint32_t> material_of_name_;
    std::uint32_t material_ = kNoMaterial;
    Mesh mesh_;
};

}  // namespace

Mesh readObj(const char* data, std::size_t size, const std::string& name, Interrupter* interrupter) {
    return ObjParser(data, size, name, interrupter).parse();
}

}  // namespace hyvox::mesh_io
