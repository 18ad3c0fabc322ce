// SPDX-License-Identifier: GPL-3.0-or-later
// The strict glTF reader (src/mesh_io/gltf_reader.h) and its JSON parser: files written here read
// back as the triangles written, through node transforms, strips, fans and every index and
// attribute encoding; damaged files are clear errors naming the object; no cut reads.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "hyvox/errors.h"
#include "hyvox/mesh_io.h"
#include "mesh_io/gltf_reader.h"
#include "mesh_io/json_value.h"
#include "support/temp_dir.h"

namespace fs = std::filesystem;
using hyvox::test::TempDir;

namespace {

template <typename T>
std::string bytesOf(const std::vector<T>& values) {
    return std::string(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
}

std::string base64(const std::string& data) {
    static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (std::size_t i = 0; i < data.size(); i += 3) {
        std::uint32_t n = std::uint32_t(static_cast<unsigned char>(data[i])) << 16;
        if (i + 1 < data.size()) n |= std::uint32_t(static_cast<unsigned char>(data[i + 1])) << 8;
        if (i + 2 < data.size()) n |= std::uint32_t(static_cast<unsigned char>(data[i + 2]));
        out += digits[(n >> 18) & 63];
        out += digits[(n >> 12) & 63];
        out += i + 1 < data.size() ? digits[(n >> 6) & 63] : '=';
        out += i + 2 < data.size() ? digits[n & 63] : '=';
    }
    return out;
}

std::string glb(const std::string& json, const std::string& bin) {
    std::string j = json, b = bin;
    while (j.size() % 4) j += ' ';
    while (b.size() % 4) b += '\0';
    auto u32 = [](std::uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
    std::string chunks = u32(std::uint32_t(j.size())) + u32(0x4E4F534A) + j;
    if (!bin.empty()) chunks += u32(std::uint32_t(b.size())) + u32(0x004E4942) + b;
    return u32(0x46546C67) + u32(2) + u32(std::uint32_t(12 + chunks.size())) + chunks;
}

// A unit square as two triangles: 4 positions, 6 uint16 indices, one buffer.
const std::vector<float> kSquare = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
const std::vector<std::uint16_t> kSquareIndices = {0, 1, 2, 0, 2, 3};

std::string squareBin() {
    std::string bin = bytesOf(kSquare) + bytesOf(kSquareIndices);
    return bin;
}

// The square's JSON with `nodes` (a JSON array), the buffer's `uri` ("" for a GLB).
std::string squareJson(const std::string& uri, const std::string& nodes = R"([{"mesh":0}])",
                       const std::string& extra = "") {
    return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":)" + nodes +
        R"(,"meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],)"
        R"("buffers":[{"byteLength":60)" +
        (uri.empty() ? "" : R"(,"uri":")" + uri + "\"") +
        R"(}],)"
        R"("bufferViews":[{"buffer":0,"byteLength":48},{"buffer":0,"byteOffset":48,"byteLength":12}],)"
        R"("accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3"},)"
        R"({"bufferView":1,"componentType":5123,"count":6,"type":"SCALAR"}])" +
        extra + "}";
}

hyvox::Mesh read(const std::string& bytes, const std::string& name = "m.glb", std::uint64_t max_bytes = 1ull << 30) {
    return hyvox::mesh_io::readGltf(bytes.data(), bytes.size(), name, max_bytes);
}

std::string errorOf(const std::string& bytes, const std::string& name = "m.glb", std::uint64_t max_bytes = 1ull << 30) {
    try {
        read(bytes, name, max_bytes);
    } catch (const hyvox::InvalidInput& e) {
        return e.what();
    } catch (const std::exception& e) {
        return std::string("(wrong exception) ") + e.what();
    }
    return "(no error)";
}

#define EXPECT_HAS(TEXT, PART) EXPECT_NE(std::string(TEXT).find(PART), std::string::npos) << (TEXT)

}  // namespace

TEST(IoGltf, GlbAndGltfReadBackTheSquare) {
    TempDir dir;
    const std::string data_uri = "data:application/octet-stream;base64," + base64(squareBin());
    const std::vector<std::pair<std::string, std::string>> files = {
        {"square.glb", glb(squareJson(""), squareBin())},
        {"square.gltf", squareJson(data_uri)},
        {"beside.gltf", squareJson("the%20buffer.bin")},  // a file beside it, its name %-escaped
    };
    dir.write("the buffer.bin", squareBin());
    for (const auto& [name, bytes] : files) {
        SCOPED_TRACE(name);
        const hyvox::Mesh mesh = hyvox::readMesh(dir.write(name, bytes).string());
        EXPECT_EQ(mesh.positions, kSquare);
        EXPECT_EQ(mesh.triangles, (std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3}));
        EXPECT_FALSE(mesh.hasColors());
        EXPECT_FALSE(mesh.hasUvs());
    }
}

TEST(IoGltf, NodeTransformsHierarchyAndInstances) {
    // Node 0: translation (10,0,0), child node 1 scaled by 2 holding the mesh; node 2 the same
    // mesh by a matrix moving it (0,0,5); the scene lists nodes 0 and 2.
    const std::string nodes = R"([{"translation":[10,0,0],"children":[1]},{"scale":[2,2,2],"mesh":0},)"
                              R"({"matrix":[1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,5,1],"mesh":0}])";
    std::string json = squareJson("", nodes);
    json.replace(json.find(R"("scenes":[{"nodes":[0]}])"), 24, R"("scenes":[{"nodes":[0,2]}])");
    const hyvox::Mesh mesh = read(glb(json, squareBin()));
    ASSERT_EQ(mesh.vertexCount(), 8u);
    const std::vector<float> expected = {10, 0, 0, 12, 0, 0, 12, 2, 0, 10, 2, 0,  // 2x, then +10 in x
                                         0,  0, 5, 1,  0, 5, 1,  1, 5, 0,  1, 5};
    EXPECT_EQ(mesh.positions, expected);
    EXPECT_EQ(mesh.triangles, (std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7}));
    // A rotation: a quarter turn about z takes (1,0,0) to (0,1,0).
    const hyvox::Mesh turned = read(
        glb(squareJson("", R"([{"rotation":[0,0,0.70710678118654752,0.70710678118654752],"mesh":0}])"), squareBin()));
    EXPECT_NEAR(turned.positions[3], 0.0f, 1e-6f);
    EXPECT_NEAR(turned.positions[4], 1.0f, 1e-6f);
}

TEST(IoGltf, StripsFansIndexTypesAndAttributes) {
    // 5 vertices; a strip of 5 corners (3 triangles) and a fan of 4 (2), ubyte and uint indices;
    // normalized ubyte RGBA colours (linear, stored sRGB-encoded) and float uvs (v flipped).
    const std::vector<float> positions = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 2, 0, 0};
    const std::vector<std::uint8_t> strip = {0, 1, 2, 3, 4, 0, 0, 0};  // padded to 4
    const std::vector<std::uint32_t> fan = {0, 1, 3, 2};
    const std::vector<std::uint8_t> colours = {255, 0, 0,   255, 0,   255, 0,   128, 0, 0,
                                               255, 0, 255, 255, 255, 255, 128, 0,   0, 255};
    const std::vector<float> uvs = {0, 0, 1, 0, 0, 1, 1, 1, 0.5f, 0.25f};
    const std::string bin = bytesOf(positions) + bytesOf(strip) + bytesOf(fan) + bytesOf(colours) + bytesOf(uvs);
    const std::string json = R"({"asset":{"version":"2.0"},"meshes":[{"primitives":[)"
                             R"({"attributes":{"POSITION":0,"COLOR_0":3,"TEXCOORD_0":4},"indices":1,"mode":5},)"
                             R"({"attributes":{"POSITION":0},"indices":2,"mode":6},)"
                             R"({"attributes":{"POSITION":0},"mode":0}]}],)"  // points: skipped
                             R"("buffers":[{"byteLength":)" +
        std::to_string(bin.size()) +
        R"(}],)"
        R"("bufferViews":[{"buffer":0,"byteLength":60},{"buffer":0,"byteOffset":60,"byteLength":8},)"
        R"({"buffer":0,"byteOffset":68,"byteLength":16},{"buffer":0,"byteOffset":84,"byteLength":20},)"
        R"({"buffer":0,"byteOffset":104,"byteLength":40}],)"
        R"("accessors":[{"bufferView":0,"componentType":5126,"count":5,"type":"VEC3"},)"
        R"({"bufferView":1,"componentType":5121,"count":5,"type":"SCALAR"},)"
        R"({"bufferView":2,"componentType":5125,"count":4,"type":"SCALAR"},)"
        R"({"bufferView":3,"componentType":5121,"normalized":true,"count":5,"type":"VEC4"},)"
        R"({"bufferView":4,"componentType":5126,"count":5,"type":"VEC2"}]})";
    const hyvox::Mesh mesh = read(glb(json, bin));  // no scene, no nodes: every mesh as it is
    ASSERT_EQ(mesh.vertexCount(), 10u);             // the position accessor once per primitive with triangles
    // The specification's strip {v_i, v_(i+1+i%2), v_(i+2-i%2)}: (0,1,2), (1,3,2), (2,3,4); its fan
    // {v_(i+1), v_(i+2), v_0}: (1,3,0), (3,2,0) of the second primitive's vertices (5..9).
    EXPECT_EQ(mesh.triangles, (std::vector<std::uint32_t>{0, 1, 2, 1, 3, 2, 2, 3, 4, 6, 8, 5, 8, 7, 5}));
    ASSERT_TRUE(mesh.hasColors());
    EXPECT_TRUE(mesh.colors_alpha);
    EXPECT_FLOAT_EQ(mesh.colors[0], 1.0f);
    EXPECT_FLOAT_EQ(mesh.colors[7], 128 / 255.0f);  // alpha stays linear
    // 128/255 linear is 0.7367 sRGB-encoded; vertices without COLOR_0 are white.
    EXPECT_NEAR(mesh.colors[4 * 4], 0.7367f, 1e-4f);
    EXPECT_FLOAT_EQ(mesh.colors[4 * 7], 1.0f);
    ASSERT_TRUE(mesh.hasUvs());
    EXPECT_EQ(std::vector<float>(mesh.uvs.begin(), mesh.uvs.begin() + 10),
              (std::vector<float>{0, 1, 1, 1, 0, 0, 1, 0, 0.5f, 0.75f}));
}

TEST(IoGltf, DamagedFilesAreErrorsNamingTheObject) {
    const std::string bin = squareBin();
    const std::string ok = squareJson("");
    auto with = [&](const std::string& from, const std::string& to) {
        std::string json = ok;
        const auto at = json.find(from);
        EXPECT_NE(at, std::string::npos) << from;
        return glb(json.replace(at, from.size(), to), bin);
    };
    EXPECT_HAS(errorOf(with(R"("count":4,)", R"("count":5,)")),
               "glTF accessors[0] needs 60 bytes of bufferViews[0], which has 48");
    EXPECT_HAS(errorOf(with(R"("byteLength":12})", R"("byteLength":13})")),
               "bufferViews[1] (bytes 48 + 13) runs past its buffer of 60");
    EXPECT_HAS(errorOf(with(R"("indices":1)", R"("indices":7)")), "names accessors[7], but the file has 2");
    EXPECT_HAS(errorOf(with(R"("count":6,)", R"("count":5,)")), "5 corners is no whole number of triangles");
    EXPECT_HAS(errorOf(with(R"([{"mesh":0}])", R"([{"mesh":0,"children":[0]}])")), "nodes[0] is reached twice");
    EXPECT_HAS(errorOf(with(R"("componentType":5126)", R"("componentType":5127)")),
               "componentType 5127 is no glTF component type");
    EXPECT_HAS(errorOf(with(R"("version":"2.0")", R"("version":"1.0")")), "only glTF 2.x is read");
    EXPECT_HAS(errorOf(with(R"("asset":)", R"("extensionsRequired":["KHR_draco_mesh_compression"],"asset":)")),
               "needs KHR_draco_mesh_compression");
    EXPECT_HAS(errorOf(with(R"("type":"SCALAR"})", R"("type":"SCALAR","sparse":{}})")), "accessors[1] is sparse");
    EXPECT_HAS(errorOf(with(R"("scene":0,)", R"("scene":0,"scene":0,)")), "the key \"scene\" appears twice");
    EXPECT_HAS(errorOf(with(R"([0]}])", R"([0],}])")), "the JSON is not valid");
    EXPECT_HAS(errorOf(glb(ok, bin.substr(0, 40))), "buffers[0] is 60 bytes but the GLB's BIN chunk holds 40");
    // An index past the vertices.
    std::string bad_bin = bin;
    bad_bin[48] = 9;
    EXPECT_HAS(errorOf(glb(ok, bad_bin)), "index 9 names none of its 4 vertices");
    // The container: cut, and its length field wrong.
    const std::string file = glb(ok, bin);
    EXPECT_HAS(errorOf(file.substr(0, file.size() - 1)), "the GLB header says");
    EXPECT_HAS(errorOf(squareJson("data:application/octet-stream;base64,@@@@"), "m.gltf"),
               "its data URI is not base64");
    EXPECT_HAS(errorOf(squareJson("missing.bin"), "/nonexistent/m.gltf"), "buffers[0]: cannot open mesh file");
    EXPECT_HAS(errorOf(squareJson("https://example.com/b.bin"), "m.gltf"), "names another place");
    // Instancing past the budget: the square on 8000 nodes, 1.3 MB, in a 1 MiB budget.
    std::string nodes = "[";
    for (int n = 0; n < 8000; ++n) nodes += std::string(n ? "," : "") + R"({"mesh":0})";
    nodes += "]";
    std::string many = squareJson("", nodes);
    std::string roots = "[";
    for (int n = 0; n < 8000; ++n) roots += (n ? "," : "") + std::to_string(n);
    many.replace(many.find(R"("scenes":[{"nodes":[0]}])"), 24, R"("scenes":[{"nodes":)" + roots + "]}]");
    EXPECT_HAS(errorOf(glb(many, bin), "m.glb", 1 << 20),
               "the scene's meshes need more than the memory budget of 1 MiB");
}

TEST(IoGltf, JsonIsStrict) {
    auto error = [](const std::string& text) {
        try {
            hyvox::mesh_io::parseJson(text.data(), text.size());
        } catch (const hyvox::mesh_io::JsonError& e) {
            return e.what;
        }
        return std::string("(no error)");
    };
    const std::string ok = R"( {"a": [1, -2.5e3, true, false, null, "x\u00e9\ud83d\ude00\n"], "b": {}} )";
    const hyvox::mesh_io::JsonValue v = hyvox::mesh_io::parseJson(ok.data(), ok.size());
    EXPECT_EQ(v.find("a")->items()[1].number(), -2500.0);
    EXPECT_EQ(v.find("a")->items()[5].string(), "x\xc3\xa9\xf0\x9f\x98\x80\n");
    for (const char* bad : {"[1,]", "{\"a\":1,}", "01", "1.", ".5", "1e", "+1", "\"\\x\"", "\"\\ud800\"", "[1] 2",
                            "\"a\x01\"", "\"\xc0\xaf\"", "1e999", "nul", "{\"a\" 1}", "[", ""})
        EXPECT_NE(error(bad), "(no error)") << bad;
    std::string deep(66, '[');
    deep += std::string(66, ']');
    EXPECT_HAS(error(deep), "nested more than 64 deep");
}

// Every cut and many byte changes of a small GLB and a small .gltf: a mesh whose indices are
// in range, or an InvalidInput; a cut never reads (only the JSON's closing whitespace may go).
TEST(IoGltf, EveryTruncationAndByteFlipIsReadOrRefused) {
    const std::string data_uri = "data:application/octet-stream;base64," + base64(squareBin());
    const std::vector<std::pair<std::string, std::string>> seeds = {{"s.glb", glb(squareJson(""), squareBin())},
                                                                    {"s.gltf", squareJson(data_uri) + "\n"}};
    std::mt19937 rng(8);
    const char interesting[] = {'\0', '\n', ' ', '-', '9', 'e', '"', '\xff', '{', '3', ',', ']'};
    for (const auto& [name, bytes] : seeds) {
        SCOPED_TRACE(name);
        std::size_t read_count = 0, refused = 0;
        const std::size_t last = bytes.find_last_not_of(" \n");
        for (std::size_t cut = 0; cut < bytes.size(); ++cut) {
            const std::vector<char> part(bytes.begin(), bytes.begin() + std::ptrdiff_t(cut));
            try {
                hyvox::mesh_io::readGltf(part.data(), part.size(), name, 1ull << 30);
                EXPECT_GT(cut, last) << "cut at " << cut;
                ++read_count;
            } catch (const hyvox::InvalidInput&) {
                ++refused;
            }
        }
        for (std::size_t i = 0; i < 8 * bytes.size(); ++i) {
            std::string changed = bytes;
            for (int n = 1 + int(rng() % 3); n > 0; --n)
                changed[rng() % changed.size()] = interesting[rng() % sizeof interesting];
            try {
                const hyvox::Mesh mesh = hyvox::mesh_io::readGltf(changed.data(), changed.size(), name, 1ull << 30);
                for (std::uint32_t index : mesh.triangles) ASSERT_LT(index, mesh.vertexCount());
                ++read_count;
            } catch (const hyvox::InvalidInput&) {
                ++refused;
            }
        }
        EXPECT_GT(read_count, 0u);
        EXPECT_GT(refused, 0u);
    }
}
