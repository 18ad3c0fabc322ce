// SPDX-License-Identifier: GPL-3.0-or-later
// glTF is read in three steps: the container (GLB chunks or the JSON text), the JSON tree
// (json_value.h), then the scene walked from its root nodes with an explicit stack, each
// node's mesh appended through accessors that were checked against their views first.
#include "mesh_io/gltf_reader.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "mesh_io/json_value.h"
#include "os/file_bytes.h"
#include "os/mesh_file_error.h"

namespace hyvox::mesh_io {
namespace {

constexpr std::uint32_t kGlbMagic = 0x46546C67;  // "glTF"
constexpr std::uint32_t kJsonChunk = 0x4E4F534A;
constexpr std::uint32_t kBinChunk = 0x004E4942;
constexpr std::uint64_t kInterruptEvery = 1 << 16;

using Matrix = std::array<double, 16>;  // column-major, as glTF writes it
constexpr Matrix kIdentity{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

Matrix multiply(const Matrix& a, const Matrix& b) {
    Matrix out{};
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) {
            double sum = 0;
            for (int k = 0; k < 4; ++k) sum += a[k * 4 + r] * b[c * 4 + k];
            out[c * 4 + r] = sum;
        }
    return out;
}

std::uint32_t u32(const char* bytes) {
    std::uint32_t value;
    std::memcpy(&value, bytes, 4);  // little-endian in the file, as on every host hyvox builds for
    return value;
}

// linear -> the sRGB encoding Mesh::colors holds.
float srgbEncoded(double linear) {
    const double c = std::min(1.0, std::max(0.0, linear));
    return float(c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055);
}

int base64Digit(char c) {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+') return 62;
    if (c == '/') return 63;
    return -1;
}

struct Accessor {
    const char* base = nullptr;  // the first element's first byte
    std::size_t stride = 0;      // bytes from one element to the next
    std::uint64_t count = 0;
    int components = 0;      // 1 (SCALAR) to 4 (VEC4)
    int component_type = 0;  // 5120 ... 5126
    bool normalized = false;
};

std::size_t componentBytes(int type) {
    switch (type) {
        case 5120:
        case 5121: return 1;
        case 5122:
        case 5123: return 2;
        case 5125:
        case 5126: return 4;
        default: return 0;
    }
}

class GltfReader {
public:
    GltfReader(const char* data, std::size_t size, const std::string& name, std::uint64_t max_bytes,
               Interrupter* interrupter)
        : data_(data), size_(size), name_(name), max_bytes_(max_bytes), interrupter_(interrupter) {}

    Mesh read() {
        const char* json = data_;
        std::size_t json_size = size_;
        if (size_ >= 4 && u32(data_) == kGlbMagic) readContainer(json, json_size);
        try {
            document_ = parseJson(json, json_size);
        } catch (const JsonError& e) {
            fail("the JSON is not valid (" + e.what + ")");
        }
        if (!document_.isObject()) fail("the JSON is not an object");
        checkAsset();
        buffers_.resize(array("buffers").size());
        walkScene();
        if (mesh_.triangles.empty()) fail("the scene holds no triangles");
        if (!any_colors_) mesh_.colors.clear();
        if (!any_uvs_) mesh_.uvs.clear();
        return std::move(mesh_);
    }

private:
    [[noreturn]] void fail(const std::string& what) const { os::failMeshFile(name_, "glTF " + what); }

    // --- the container ------------------------------------------------------------------

    void readContainer(const char*& json, std::size_t& json_size) {
        if (size_ < 20) fail("the GLB file ends inside its header");
        if (u32(data_ + 4) != 2) fail("GLB version " + std::to_string(u32(data_ + 4)) + " (only 2 is read)");
        if (u32(data_ + 8) != size_)
            fail("the GLB header says " + std::to_string(u32(data_ + 8)) + " bytes but the file has " +
                 std::to_string(size_) + " (truncated, or the length is wrong)");
        std::size_t at = 12;
        for (int chunk = 0; at < size_; ++chunk) {
            if (size_ - at < 8) fail("the GLB file ends inside a chunk header");
            const std::uint32_t length = u32(data_ + at), type = u32(data_ + at + 4);
            at += 8;
            if (length > size_ - at) fail("GLB chunk " + std::to_string(chunk) + " runs past the end of the file");
            if (chunk == 0) {
                if (type != kJsonChunk) fail("the first GLB chunk is not JSON");
                json = data_ + at;
                json_size = length;
            } else if (chunk == 1 && type == kBinChunk) {
                bin_ = data_ + at;
                bin_size_ = length;
            }
            at += length;  // other chunks are for extensions: skipped, as the format says
        }
        if (!json) fail("the GLB file has no JSON chunk");
        glb_ = true;
    }

    // --- the JSON tree --------------------------------------------------------------------

    const std::vector<JsonValue>& array(const char* key) const {
        static const std::vector<JsonValue> none;
        const JsonValue* value = document_.find(key);
        if (!value) return none;
        if (!value->isArray()) fail(std::string("'") + key + "' is not an array");
        return value->items();
    }

    // The object `key`[index], checked.
    const JsonValue& object(const char* key, std::uint64_t index, const std::string& by) const {
        const std::vector<JsonValue>& all = array(key);
        if (index >= all.size())
            fail(by + " names " + key + "[" + std::to_string(index) + "], but the file has " +
                 std::to_string(all.size()));
        if (!all[index].isObject()) fail(std::string(key) + "[" + std::to_string(index) + "] is not an object");
        return all[index];
    }

    // A whole number in [0, max] held by `value` (which `what` names in errors).
    std::uint64_t whole(const JsonValue& value, const std::string& what, double max = 9007199254740992.0) const {
        if (!value.isNumber() || value.number() < 0 || value.number() > max ||
            value.number() != std::floor(value.number()))
            fail(what + " is not a whole number from 0 to " + std::to_string(std::uint64_t(max)));
        return std::uint64_t(value.number());
    }

    // Member `key` of `owner` as a whole number, `fallback` when it is absent (-1: required).
    std::uint64_t member(const JsonValue& owner, const char* key, const std::string& what, std::int64_t fallback = -1,
                         double max = 9007199254740992.0) const {
        const JsonValue* value = owner.find(key);
        if (!value) {
            if (fallback < 0) fail(what + " has no '" + key + "'");
            return std::uint64_t(fallback);
        }
        return whole(*value, what + "." + key, max);
    }

    void checkAsset() {
        const JsonValue* asset = document_.find("asset");
        const JsonValue* version = asset ? asset->find("version") : nullptr;
        if (!version || !version->isString()) fail("the file has no asset.version");
        if (version->string().rfind("2.", 0) != 0)
            fail("version " + version->string().substr(0, 20) + " (only glTF 2.x is read)");
        for (const JsonValue& required : array("extensionsRequired")) {
            if (!required.isString()) fail("extensionsRequired holds a non-string");
            const std::string& e = required.string();
            // What changes the geometry must be understood; the rest (materials, lights,
            // texture transforms) does not matter to voxels.
            if (e == "KHR_draco_mesh_compression" || e == "EXT_meshopt_compression" || e == "KHR_meshopt_compression")
                fail("the file needs " + e + ", compressed geometry hyvox does not read; write it uncompressed");
            if (e == "EXT_mesh_gpu_instancing") fail("the file needs " + e + ", which hyvox does not read");
        }
    }

    // --- buffers and accessors ------------------------------------------------------------

    struct LoadedBuffer {
        bool loaded = false;
        const char* data = nullptr;
        std::uint64_t size = 0;  // byteLength
        std::vector<char> owned;
    };

    std::string folder() const {
        const auto slash = name_.find_last_of('/');
        return slash == std::string::npos ? "." : name_.substr(0, slash);
    }

    std::vector<char> decodeBase64(std::string_view text, const std::string& what) const {
        std::vector<char> out;
        out.reserve(text.size() / 4 * 3);
        std::uint32_t bits = 0;
        int held = 0;
        std::size_t n = 0;
        for (; n < text.size() && text[n] != '='; ++n) {
            const int digit = base64Digit(text[n]);
            if (digit < 0) fail(what + ": its data URI is not base64");
            bits = (bits << 6) | std::uint32_t(digit);
            held += 6;
            if (held >= 8) {
                held -= 8;
                out.push_back(char((bits >> held) & 0xFF));
            }
        }
        for (; n < text.size(); ++n)
            if (text[n] != '=') fail(what + ": its data URI is not base64");
        return out;
    }

    std::string percentDecoded(const std::string& uri, const std::string& what) const {
        std::string out;
        for (std::size_t i = 0; i < uri.size(); ++i) {
            if (uri[i] != '%') {
                out += uri[i];
                continue;
            }
            if (i + 2 >= uri.size() || !std::isxdigit(static_cast<unsigned char>(uri[i + 1])) ||
                !std::isxdigit(static_cast<unsigned char>(uri[i + 2])))
                fail(what + ": its uri has a bad %-escape");
            out += char(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
            i += 2;
        }
        return out;
    }

    const LoadedBuffer& buffer(std::uint64_t index, const std::string& by) {
        const JsonValue& b = object("buffers", index, by);
        LoadedBuffer& loaded = buffers_[index];
        if (loaded.loaded) return loaded;
        const std::string what = "buffers[" + std::to_string(index) + "]";
        loaded.size = member(b, "byteLength", what, -1);
        const JsonValue* uri = b.find("uri");
        if (!uri) {
            if (!glb_ || index != 0 || !bin_) fail(what + " has no uri (only a GLB's first buffer is its BIN chunk)");
            if (loaded.size > bin_size_)
                fail(what + " is " + std::to_string(loaded.size) + " bytes but the GLB's BIN chunk holds " +
                     std::to_string(bin_size_));
            loaded.data = bin_;
        } else {
            if (!uri->isString()) fail(what + ".uri is not a string");
            const std::string& text = uri->string();
            if (text.rfind("data:", 0) == 0) {
                const auto comma = text.find(',');
                if (comma == std::string::npos || comma < 12 || text.compare(comma - 7, 7, ";base64") != 0)
                    fail(what + ": only base64 data URIs are read");
                loaded.owned = decodeBase64(std::string_view(text).substr(comma + 1), what);
            } else {
                if (text.find("://") != std::string::npos)
                    fail(what + ": its uri names another place (" + text.substr(0, 60) +
                         "), not a file beside this one");
                const std::string path = folder() + "/" + percentDecoded(text, what);
                try {
                    loaded.owned = os::readFileBytes(
                        path,
                        std::size_t(std::min<std::uint64_t>(max_bytes_, std::numeric_limits<std::size_t>::max())));
                } catch (const InvalidInput& e) {
                    fail(what + ": " + e.what());
                }
            }
            if (loaded.owned.size() < loaded.size)
                fail(what + " is " + std::to_string(loaded.size) + " bytes but its data holds " +
                     std::to_string(loaded.owned.size()));
            loaded.data = loaded.owned.data();
        }
        loaded.loaded = true;
        return loaded;
    }

    // The accessor, checked: its view and buffer exist, its elements lie inside the view.
    Accessor accessor(std::uint64_t index, const std::string& by) {
        const JsonValue& a = object("accessors", index, by);
        const std::string what = "accessors[" + std::to_string(index) + "]";
        if (a.find("sparse")) fail(what + " is sparse, which hyvox does not read");
        if (!a.find("bufferView")) fail(what + " has no bufferView (data that is all zeros is not read)");
        Accessor out;
        out.component_type = int(member(a, "componentType", what, -1, 1e9));
        const std::size_t component = componentBytes(out.component_type);
        if (component == 0)
            fail(what + ".componentType " + std::to_string(out.component_type) + " is no glTF component type");
        const JsonValue* type = a.find("type");
        if (!type || !type->isString()) fail(what + " has no type");
        const std::string& t = type->string();
        out.components = t == "SCALAR" ? 1 : t == "VEC2" ? 2 : t == "VEC3" ? 3 : t == "VEC4" ? 4 : 0;
        if (out.components == 0) fail(what + ".type " + t.substr(0, 20) + " is not read (SCALAR, VEC2, VEC3, VEC4)");
        if (const JsonValue* n = a.find("normalized")) {
            if (n->type() != JsonValue::Type::Bool) fail(what + ".normalized is not true or false");
            out.normalized = n->boolean();
        }
        out.count = member(a, "count", what, -1);
        if (out.count == 0) fail(what + ".count is 0");
        const std::uint64_t offset = member(a, "byteOffset", what, 0);
        const std::uint64_t view_index = member(a, "bufferView", what, -1);
        const JsonValue& view = object("bufferViews", view_index, what);
        const std::string view_what = "bufferViews[" + std::to_string(view_index) + "]";
        const std::uint64_t view_offset = member(view, "byteOffset", view_what, 0);
        const std::uint64_t view_length = member(view, "byteLength", view_what, -1);
        const std::uint64_t element = component * std::uint64_t(out.components);
        out.stride = std::size_t(member(view, "byteStride", view_what, std::int64_t(element), 252));
        if (out.stride < element)
            fail(view_what + ".byteStride " + std::to_string(out.stride) + " is less than an element of " + what);
        const LoadedBuffer& b = buffer(member(view, "buffer", view_what, -1), view_what);
        if (view_offset > b.size || view_length > b.size - view_offset)
            fail(view_what + " (bytes " + std::to_string(view_offset) + " + " + std::to_string(view_length) +
                 ") runs past its buffer of " + std::to_string(b.size));
        // In doubles first: a count of 2^53 must not wrap.
        const double need = double(offset) + double(out.stride) * double(out.count - 1) + double(element);
        if (need > double(view_length))
            fail(what + " needs " + std::to_string(std::uint64_t(need)) + " bytes of " + view_what + ", which has " +
                 std::to_string(view_length) + " (a count or length is wrong)");
        out.base = b.data + view_offset + offset;
        return out;
    }

    // Element i's component c as a number (normalized integers to 0..1 or -1..1).
    static double value(const Accessor& a, std::uint64_t i, int c) {
        const char* p = a.base + i * a.stride + std::size_t(c) * componentBytes(a.component_type);
        auto load = [p](auto zero) {
            decltype(zero) v;
            std::memcpy(&v, p, sizeof v);
            return v;
        };
        switch (a.component_type) {
            case 5120:
                return a.normalized ? std::max(double(load(std::int8_t{})) / 127.0, -1.0) : double(load(std::int8_t{}));
            case 5121: return a.normalized ? double(load(std::uint8_t{})) / 255.0 : double(load(std::uint8_t{}));
            case 5122:
                return a.normalized ? std::max(double(load(std::int16_t{})) / 32767.0, -1.0)
                                    : double(load(std::int16_t{}));
            case 5123: return a.normalized ? double(load(std::uint16_t{})) / 65535.0 : double(load(std::uint16_t{}));
            case 5125: return double(load(std::uint32_t{}));
            default: return double(load(float{}));
        }
    }

    // --- the scene ------------------------------------------------------------------------

    Matrix nodeMatrix(const JsonValue& node, const std::string& what) const {
        auto numbers = [&](const char* key, std::size_t n) -> std::vector<double> {
            const JsonValue* value = node.find(key);
            if (!value) return {};
            if (!value->isArray() || value->items().size() != n)
                fail(what + "." + key + " is not " + std::to_string(n) + " numbers");
            std::vector<double> out;
            for (const JsonValue& x : value->items()) {
                if (!x.isNumber()) fail(what + "." + key + " is not " + std::to_string(n) + " numbers");
                out.push_back(x.number());
            }
            return out;
        };
        const std::vector<double> m = numbers("matrix", 16);
        if (!m.empty()) {
            Matrix out;
            std::copy(m.begin(), m.end(), out.begin());
            return out;
        }
        std::vector<double> t = numbers("translation", 3), r = numbers("rotation", 4), s = numbers("scale", 3);
        if (t.empty()) t = {0, 0, 0};
        if (r.empty()) r = {0, 0, 0, 1};
        if (s.empty()) s = {1, 1, 1};
        const double x = r[0], y = r[1], z = r[2], w = r[3];
        // T * R * S, column-major.
        const double rot[9] = {1 - 2 * (y * y + z * z), 2 * (x * y + z * w),     2 * (x * z - y * w),
                               2 * (x * y - z * w),     1 - 2 * (x * x + z * z), 2 * (y * z + x * w),
                               2 * (x * z + y * w),     2 * (y * z - x * w),     1 - 2 * (x * x + y * y)};
        Matrix out{};
        for (int c = 0; c < 3; ++c)
            for (int row = 0; row < 3; ++row) out[c * 4 + row] = rot[c * 3 + row] * s[std::size_t(c)];
        out[12] = t[0];
        out[13] = t[1];
        out[14] = t[2];
        out[15] = 1;
        return out;
    }

    std::vector<std::uint64_t> indexList(const JsonValue& owner, const char* key, const std::string& what) const {
        std::vector<std::uint64_t> out;
        const JsonValue* list = owner.find(key);
        if (!list) return out;
        if (!list->isArray()) fail(what + "." + key + " is not an array");
        for (const JsonValue& i : list->items()) out.push_back(whole(i, what + "." + key + "[]"));
        return out;
    }

    void walkScene() {
        const std::vector<JsonValue>& nodes = array("nodes");
        std::vector<std::uint64_t> roots;
        if (!array("scenes").empty()) {
            const std::uint64_t scene = member(document_, "scene", "the file", 0);
            roots = indexList(object("scenes", scene, "'scene'"), "nodes", "scenes[" + std::to_string(scene) + "]");
        } else if (!nodes.empty()) {
            // No scene: every node that is no node's child.
            std::vector<bool> child(nodes.size(), false);
            for (std::size_t n = 0; n < nodes.size(); ++n)
                for (std::uint64_t c :
                     indexList(object("nodes", n, "the file"), "children", "nodes[" + std::to_string(n) + "]"))
                    if (c < child.size()) child[c] = true;
            for (std::size_t n = 0; n < nodes.size(); ++n)
                if (!child[n]) roots.push_back(n);
        } else {
            // No nodes either: every mesh as it is.
            for (std::size_t m = 0; m < array("meshes").size(); ++m) appendMesh(m, kIdentity, "the file");
            return;
        }
        std::vector<bool> seen(nodes.size(), false);
        std::vector<std::pair<std::uint64_t, Matrix>> stack;
        for (auto r = roots.rbegin(); r != roots.rend(); ++r) stack.emplace_back(*r, kIdentity);
        while (!stack.empty()) {
            const auto [index, parent] = stack.back();
            stack.pop_back();
            const std::string what = "nodes[" + std::to_string(index) + "]";
            const JsonValue& node = object("nodes", index, "a scene or node");
            if (seen[index]) fail(what + " is reached twice (a cycle, or a node with two parents)");
            seen[index] = true;
            const Matrix world = multiply(parent, nodeMatrix(node, what));
            if (node.find("mesh")) appendMesh(member(node, "mesh", what), world, what);
            const std::vector<std::uint64_t> children = indexList(node, "children", what);
            for (auto c = children.rbegin(); c != children.rend(); ++c) stack.emplace_back(*c, world);
        }
    }

    void appendMesh(std::uint64_t index, const Matrix& world, const std::string& by) {
        const JsonValue& m = object("meshes", index, by);
        const std::string what = "meshes[" + std::to_string(index) + "]";
        const JsonValue* primitives = m.find("primitives");
        if (!primitives || !primitives->isArray()) fail(what + " has no primitives");
        for (std::size_t p = 0; p < primitives->items().size(); ++p)
            appendPrimitive(primitives->items()[p], world, what + ".primitives[" + std::to_string(p) + "]");
    }

    void appendPrimitive(const JsonValue& primitive, const Matrix& world, const std::string& what) {
        throwIfInterrupted(interrupter_);
        if (!primitive.isObject()) fail(what + " is not an object");
        if (const JsonValue* extensions = primitive.find("extensions"))
            if (extensions->find("KHR_draco_mesh_compression"))
                fail(what + " is Draco-compressed, which hyvox does not read; write the file uncompressed");
        const std::uint64_t mode = member(primitive, "mode", what, 4, 6);
        if (mode < 4) return;  // points and lines: nothing to voxelize
        const JsonValue* attributes = primitive.find("attributes");
        if (!attributes || !attributes->isObject() || !attributes->find("POSITION")) fail(what + " has no POSITION");
        const Accessor positions = accessor(member(*attributes, "POSITION", what + ".attributes"), what);
        if (positions.components != 3) fail(what + ": POSITION is not VEC3");
        const std::uint64_t first = mesh_.vertexCount();
        if (first + positions.count > std::numeric_limits<std::uint32_t>::max())
            fail("more vertices than 32-bit indices can number");

        std::uint64_t corners = positions.count;
        Accessor indices;
        const bool indexed = primitive.find("indices") != nullptr;
        if (indexed) {
            indices = accessor(member(primitive, "indices", what), what);
            if (indices.components != 1 || indices.normalized ||
                (indices.component_type != 5121 && indices.component_type != 5123 && indices.component_type != 5125))
                fail(what + ": its indices are not unsigned integer scalars");
            corners = indices.count;
        }
        const std::uint64_t triangles = mode == 4 ? corners / 3 : corners >= 3 ? corners - 2 : 0;
        if (mode == 4 && corners % 3 != 0)
            fail(what + ": " + std::to_string(corners) + " corners is no whole number of triangles");
        // What this instance adds, against the budget: a small file may instance a mesh often.
        const double adds = double(positions.count) * (12.0 + 16.0 + 8.0) + double(triangles) * 12.0;
        made_bytes_ += adds;
        if (made_bytes_ > double(max_bytes_))
            fail("the scene's meshes need more than the memory budget of " + std::to_string(max_bytes_ >> 20) +
                 " MiB (memory_budget_mib)");

        appendVertices(*attributes, positions, world, what);
        mesh_.triangles.reserve(mesh_.triangles.size() + 3 * triangles);
        auto corner = [&](std::uint64_t i) -> std::uint32_t {
            if (i % kInterruptEvery == 0) throwIfInterrupted(interrupter_);
            const std::uint64_t v = indexed ? std::uint64_t(value(indices, i, 0)) : i;
            if (v >= positions.count)
                fail(what + ": index " + std::to_string(v) + " names none of its " + std::to_string(positions.count) +
                     " vertices");
            return std::uint32_t(first + v);
        };
        for (std::uint64_t t = 0; t < triangles; ++t) {
            std::uint64_t a, b, c;
            if (mode == 4) {
                a = 3 * t, b = 3 * t + 1, c = 3 * t + 2;
            } else if (mode == 5) {  // strip: every other triangle turned to keep the winding
                a = t, b = t + 1 + t % 2, c = t + 2 - t % 2;
            } else {  // fan
                a = t + 1, b = t + 2, c = 0;
            }
            mesh_.triangles.insert(mesh_.triangles.end(), {corner(a), corner(b), corner(c)});
        }
    }

    void appendVertices(const JsonValue& attributes, const Accessor& positions, const Matrix& world,
                        const std::string& what) {
        const bool identity = world == kIdentity;
        for (std::uint64_t i = 0; i < positions.count; ++i) {
            if (i % kInterruptEvery == 0) throwIfInterrupted(interrupter_);
            const double p[3] = {value(positions, i, 0), value(positions, i, 1), value(positions, i, 2)};
            for (int r = 0; r < 3; ++r)
                mesh_.positions.push_back(
                    identity ? float(p[r])
                             : float(world[r] * p[0] + world[4 + r] * p[1] + world[8 + r] * p[2] + world[12 + r]));
        }
        const JsonValue* color = attributes.find("COLOR_0");
        if (color) {
            const Accessor c = accessor(whole(*color, what + ".attributes.COLOR_0"), what);
            if (c.count != positions.count || (c.components != 3 && c.components != 4))
                fail(what + ": COLOR_0 is not one VEC3 or VEC4 per vertex");
            if (c.component_type != 5126 && !(c.normalized && (c.component_type == 5121 || c.component_type == 5123)))
                fail(what + ": COLOR_0 is neither float nor normalized unsigned bytes or shorts");
            any_colors_ = true;
            mesh_.colors_alpha |= c.components == 4;
            for (std::uint64_t i = 0; i < c.count; ++i)
                mesh_.colors.insert(
                    mesh_.colors.end(),
                    {srgbEncoded(value(c, i, 0)), srgbEncoded(value(c, i, 1)), srgbEncoded(value(c, i, 2)),
                     c.components == 4 ? float(std::min(1.0, std::max(0.0, value(c, i, 3)))) : 1.0f});
        } else {
            mesh_.colors.insert(mesh_.colors.end(), 4 * positions.count, 1.0f);
        }
        const JsonValue* uv = attributes.find("TEXCOORD_0");
        if (uv) {
            const Accessor t = accessor(whole(*uv, what + ".attributes.TEXCOORD_0"), what);
            if (t.count != positions.count || t.components != 2) fail(what + ": TEXCOORD_0 is not one VEC2 per vertex");
            any_uvs_ = true;
            for (std::uint64_t i = 0; i < t.count; ++i)
                mesh_.uvs.insert(mesh_.uvs.end(), {float(value(t, i, 0)), float(1.0 - value(t, i, 1))});
        } else {
            mesh_.uvs.insert(mesh_.uvs.end(), 2 * positions.count, 0.0f);
        }
    }

    const char* data_;
    std::size_t size_;
    const std::string& name_;
    std::uint64_t max_bytes_;
    Interrupter* interrupter_;
    bool glb_ = false;
    const char* bin_ = nullptr;
    std::size_t bin_size_ = 0;
    JsonValue document_;
    std::vector<LoadedBuffer> buffers_;
    double made_bytes_ = 0;
    bool any_colors_ = false, any_uvs_ = false;
    Mesh mesh_;
};

}  // namespace

Mesh readGltf(const char* data, std::size_t size, const std::string& name, std::uint64_t max_bytes,
              Interrupter* interrupter) {
    return GltfReader(data, size, name, max_bytes, interrupter).read();
}

}  // namespace hyvox::mesh_io
