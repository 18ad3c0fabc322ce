// SPDX-License-Identifier: GPL-3.0-or-later
// The strict STL and OFF readers (src/mesh_io/stl_reader.h, off_reader.h): files written here read
// back as the triangles written, damaged files are clear errors naming the file and the
// place, no cut of a file reads as a shorter mesh, and a format hyvox does not read is
// refused by name.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <random>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "hyvox/errors.h"
#include "hyvox/mesh_io.h"
#include "mesh_io/off_reader.h"
#include "mesh_io/stl_reader.h"
#include "support/read_error.h"
#include "support/temp_dir.h"

namespace fs = std::filesystem;
using hyvox::test::TempDir;

namespace {

struct Triangles {
    std::vector<float> positions;          // 3 per vertex
    std::vector<std::uint32_t> triangles;  // 3 per triangle
};

// `count` triangles over `vertices` random positions (so corners are shared, as in a mesh).
Triangles sample(std::size_t vertices, std::size_t count, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> coord(-100.0f, 100.0f);
    Triangles t;
    for (std::size_t i = 0; i < 3 * vertices; ++i) t.positions.push_back(coord(rng));
    std::uniform_int_distribution<std::uint32_t> index(0, std::uint32_t(vertices) - 1);
    for (std::size_t i = 0; i < 3 * count; ++i) t.triangles.push_back(index(rng));
    return t;
}

std::string number(float value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", value);
    return text;
}

std::string stlBinary(const Triangles& t, const std::string& header = "written by test_io_mesh_formats") {
    std::string out = header;
    out.resize(80, ' ');
    const std::uint32_t count = std::uint32_t(t.triangles.size() / 3);
    out.append(reinterpret_cast<const char*>(&count), 4);
    for (std::size_t f = 0; f < count; ++f) {
        const float normal[3] = {0, 0, 1};
        out.append(reinterpret_cast<const char*>(normal), 12);
        for (int c = 0; c < 3; ++c)
            out.append(reinterpret_cast<const char*>(&t.positions[3 * t.triangles[3 * f + c]]), 12);
        out += std::string("\x07\x00", 2);  // the attribute bytes: not used
    }
    return out;
}

std::string stlAscii(const Triangles& t) {
    std::string out = "solid test part\n";
    for (std::size_t f = 0; f < t.triangles.size() / 3; ++f) {
        out += "  facet normal 0 0 1\n    outer loop\n";
        for (int c = 0; c < 3; ++c) {
            const float* p = &t.positions[3 * t.triangles[3 * f + c]];
            out += "      vertex " + number(p[0]) + " " + number(p[1]) + " " + number(p[2]) + "\n";
        }
        out += "    endloop\n  endfacet\n";
    }
    return out + "endsolid test part\n";
}

std::string off(const Triangles& t) {
    std::string out = "OFF\n# a comment line\n" + std::to_string(t.positions.size() / 3) + " " +
        std::to_string(t.triangles.size() / 3) + " 0\n";
    for (std::size_t v = 0; v < t.positions.size() / 3; ++v)
        out += number(t.positions[3 * v]) + " " + number(t.positions[3 * v + 1]) + " " +
            number(t.positions[3 * v + 2]) + "\n";
    for (std::size_t f = 0; f < t.triangles.size() / 3; ++f)
        out += "3 " + std::to_string(t.triangles[3 * f]) + " " + std::to_string(t.triangles[3 * f + 1]) + " " +
            std::to_string(t.triangles[3 * f + 2]) + "\n";
    return out;
}

// The triangles as corner positions, in order: what a reader must return whatever it does
// with the vertices.
std::vector<float> corners(const std::vector<float>& positions, const std::vector<std::uint32_t>& triangles) {
    std::vector<float> out;
    for (std::uint32_t i : triangles) out.insert(out.end(), &positions[3 * i], &positions[3 * i] + 3);
    return out;
}
std::vector<float> corners(const hyvox::Mesh& m) { return corners(m.positions, m.triangles); }
std::vector<float> corners(const Triangles& t) { return corners(t.positions, t.triangles); }

std::size_t distinctPositions(const Triangles& t) {
    std::set<std::vector<float>> seen;
    for (std::uint32_t i : t.triangles)
        seen.insert({t.positions[3 * i], t.positions[3 * i + 1], t.positions[3 * i + 2]});
    return seen.size();
}

}  // namespace

TEST(IoMeshFormats, StlReadsBackWeldedInBothForms) {
    TempDir dir;
    const Triangles t = sample(40, 70, 1);
    for (const auto& [name, bytes] : {std::pair<std::string, std::string>{"b.stl", stlBinary(t)},
                                      {"a.stl", stlAscii(t)},
                                      // a binary file whose free header starts like the ASCII form
                                      {"solid_header.stl", stlBinary(t, "solid but binary")},
                                      {"upper.STL", stlAscii(t)}}) {
        SCOPED_TRACE(name);
        const hyvox::Mesh mesh = hyvox::readMesh(dir.write(name, bytes).string());
        EXPECT_EQ(corners(mesh), corners(t));
        EXPECT_EQ(mesh.vertexCount(), distinctPositions(t));  // corners at equal positions are one vertex
        EXPECT_FALSE(mesh.hasColors());
    }
    // Several solids one after the other are one mesh.
    const Triangles u = sample(10, 5, 2);
    const hyvox::Mesh two = hyvox::readMesh(dir.write("two.stl", stlAscii(t) + stlAscii(u)).string());
    std::vector<float> both = corners(t);
    const std::vector<float> second = corners(u);
    both.insert(both.end(), second.begin(), second.end());
    EXPECT_EQ(corners(two), both);
}

TEST(IoMeshFormats, DamagedStlIsAnErrorNamingThePlace) {
    TempDir dir;
    const Triangles t = sample(10, 6, 3);
    const std::string binary = stlBinary(t), ascii = stlAscii(t);
    EXPECT_READ_ERROR(dir.write("short.stl", binary.substr(0, binary.size() - 1)), "declares 6 triangles (384 bytes)",
                      "has 383 bytes");
    EXPECT_READ_ERROR(dir.write("long.stl", binary + "x"), "declares 6 triangles", "has 385 bytes");
    EXPECT_READ_ERROR(dir.write("header.stl", binary.substr(0, 50)), "shorter than a binary STL's 84-byte header");
    std::string counted = binary;
    counted[80] = 5;  // one triangle fewer than the records
    EXPECT_READ_ERROR(dir.write("count.stl", counted), "declares 5 triangles");
    EXPECT_READ_ERROR(dir.write("empty.stl", stlBinary(Triangles{})), "contains no triangles");
    EXPECT_READ_ERROR(dir.write("cut.stl", ascii.substr(0, ascii.find("endsolid"))), "no 'endsolid'", "truncated");
    std::string bad_number = ascii;
    bad_number.replace(bad_number.find("vertex ") + 7, 1, "x");
    EXPECT_READ_ERROR(dir.write("number.stl", bad_number), "line 4:", "is not a number");
    std::string two_corners = ascii;
    const auto third = two_corners.find("vertex", two_corners.find("vertex", two_corners.find("vertex") + 1) + 1);
    two_corners.erase(third, two_corners.find('\n', third) + 1 - third);
    EXPECT_READ_ERROR(dir.write("corners.stl", two_corners), "expected 'vertex', found 'endloop'");
    EXPECT_READ_ERROR(dir.write("after.stl", ascii + "3 0 1 2\n"), "expected 'solid'");
    EXPECT_READ_ERROR(dir.write("nofacet.stl", "solid x\nendsolid x\n"), "contains no triangles");
}

TEST(IoMeshFormats, OffReadsBackWithItsVariants) {
    TempDir dir;
    const Triangles t = sample(30, 50, 4);
    const hyvox::Mesh mesh = hyvox::readMesh(dir.write("m.off", off(t)).string());
    EXPECT_EQ(mesh.positions, t.positions);  // OFF lists vertices: they are kept as listed
    EXPECT_EQ(mesh.triangles, t.triangles);
    // Polygons fan-triangulated, comments anywhere, no edge count, a face colour; COFF with
    // integer and with fractional colours, NOFF with normals.
    const std::string text =
        "OFF # keyword\n4 2\n0 0 0\n1 0 0 # trailing comment\n1 1 0\n\n0 1 0\n# between\n4 0 1 2 3 255 0 0\n3 0 2 1 "
        "0.5\n";
    const hyvox::Mesh quad = hyvox::readMesh(dir.write("quad.off", text).string());
    EXPECT_EQ(quad.triangles, (std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3, 0, 2, 1}));
    EXPECT_FALSE(quad.hasColors());  // face colours are not used
    const hyvox::Mesh bytes = hyvox::readMesh(dir.write("c.off",
                                                        "COFF\n3 1 0\n0 0 0 255 0 0 255\n1 0 0 0 255 0 128\n"
                                                        "0 1 0 0 0 255 255\n3 0 1 2\n")
                                                  .string());
    EXPECT_EQ(bytes.colors, (std::vector<float>{1, 0, 0, 1, 0, 1, 0, 128 / 255.0f, 0, 0, 1, 1}));
    EXPECT_TRUE(bytes.colors_alpha);
    const hyvox::Mesh fractions = hyvox::readMesh(
        dir.write("f.off", "COFF\n3 1\n0 0 0 1 0 0\n1 0 0 0 0.5 0\n0 1 0 0 0 0.25\n3 0 1 2\n").string());
    EXPECT_EQ(fractions.colors, (std::vector<float>{1, 0, 0, 1, 0, 0.5f, 0, 1, 0, 0, 0.25f, 1}));
    EXPECT_FALSE(fractions.colors_alpha);
    const hyvox::Mesh normals =
        hyvox::readMesh(dir.write("n.off", "NOFF\n3 1\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n").string());
    EXPECT_EQ(normals.positions, (std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0}));
}

TEST(IoMeshFormats, DamagedOffIsAnErrorNamingThePlace) {
    TempDir dir;
    // The file of the issue: an OFF cut inside its face list (assimp aborted on it).
    EXPECT_READ_ERROR(fs::path(HYVOX_REGRESSION_MESHES) / "off_cut_in_face_list.off",
                      "the file is truncated or a count is wrong");
    const std::string head = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n";
    EXPECT_READ_ERROR(dir.write("index.off", head + "3 0 1 3\n"),
                      "line 6:", "vertex index 3 names none of the 3 vertices");
    EXPECT_READ_ERROR(dir.write("two.off", head + "2 0 1\n"), "face 0 has 2 corners");
    EXPECT_READ_ERROR(dir.write("missing.off", head + "3 0 1\n"), "face 0 declares 3 corners but lists 2");
    EXPECT_READ_ERROR(dir.write("after.off", head + "3 0 1 2\n3 0 1 2\n"),
                      "more after the 1 faces the header declares");
    EXPECT_READ_ERROR(dir.write("colour.off", head + "3 0 1 2 7 7\n"), "a face colour has 1, 3 or 4");
    EXPECT_READ_ERROR(dir.write("vertex.off", "OFF\n3 1 0\n0 0 0 5\n1 0 0\n0 1 0\n3 0 1 2\n"), "vertex 0 has 4 values");
    EXPECT_READ_ERROR(dir.write("huge.off", "OFF\n4000000000 4000000000\n0 0 0\n"),
                      "more than the 7 bytes after them can hold");
    EXPECT_READ_ERROR(dir.write("4d.off", "4OFF\n3 1\n"), "another dimension");
    EXPECT_READ_ERROR(dir.write("binary.off", "OFF BINARY\n"), "binary OFF is not read");
    EXPECT_READ_ERROR(dir.write("word.off", "OFF\n3 x\n"), "'x' is not a face count");
}

// A count lowered by damage (or pieces of another file after the last element) would drop the
// records past it without a word: only whitespace may follow the last element of a PLY.
TEST(IoMeshFormats, PlyRecordsPastTheDeclaredCountsAreRefused) {
    TempDir dir;
    const std::string header =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
        "property float z\nelement face FACES\nproperty list uchar int vertex_indices\nend_header\n";
    const std::string body = "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 2 1\n";
    auto with = [&](const char* faces) {
        std::string h = header;
        return h.replace(h.find("FACES"), 5, faces) + body;
    };
    EXPECT_EQ(hyvox::readMesh(dir.write("ok.ply", with("2") + "\n \r\n").string()).triangleCount(), 2u);
    EXPECT_READ_ERROR(dir.write("lowered.ply", with("1")), "bytes follow the last element the header declares (face)");
    // Binary: a face record (13 bytes) left over.
    std::string binary =
        "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
        "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
    const float xyz[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    binary.append(reinterpret_cast<const char*>(xyz), sizeof xyz);
    for (int f = 0; f < 2; ++f) {
        const std::int32_t corners[3] = {0, 1, 2};
        binary += char(3);
        binary.append(reinterpret_cast<const char*>(corners), sizeof corners);
    }
    EXPECT_READ_ERROR(dir.write("lowered_binary.ply", binary), "13 bytes follow the last element");
}

// A text file without an end marker cut inside its last number ("11" cut to "1") reads as
// another mesh: ASCII PLY and OFF ask for a line end after their last line.
TEST(IoMeshFormats, TextFilesCutInsideTheirLastNumberAreRefused) {
    TempDir dir;
    std::string points;
    for (int v = 0; v < 12; ++v)
        points += std::to_string(v % 2) + " " + std::to_string(v / 2) + " " + std::to_string(v % 3) + "\n";
    const std::string off = "OFF\n12 1 0\n" + points + "3 0 1 11";
    const std::string ply =
        "ply\nformat ascii 1.0\nelement vertex 12\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 1\nproperty list uchar int vertex_indices\nend_header\n" +
        points + "3 0 1 11";
    for (const auto& [name, text] : {std::pair{"mesh.off", off}, std::pair{"mesh.ply", ply}}) {
        const hyvox::Mesh whole = hyvox::readMesh(dir.write(name, text + "\n").string());
        ASSERT_EQ(whole.triangles, (std::vector<std::uint32_t>{0, 1, 11})) << name;
        EXPECT_EQ(hyvox::readMesh(dir.write(name, text + " \r\n\n").string()).triangles, whole.triangles) << name;
        EXPECT_READ_ERROR(dir.write(name, text), "the file ends inside its last line, with no line end after it");
        EXPECT_READ_ERROR(dir.write(name, text.substr(0, text.size() - 1)), "the file ends inside its last line");
    }
}

TEST(IoMeshFormats, AFormatHyvoxDoesNotReadIsRefusedByName) {
    TempDir dir;
    const char* offered = ".ply, .obj, .stl, .off, .gltf, .glb, .fbx, .3mf";
    EXPECT_READ_ERROR(dir.write("scene.blend", "BLENDER"), "'.blend' is not a format hyvox reads", offered);
    EXPECT_READ_ERROR(dir.write("model.3ds", "MM"), "'.3ds' is not a format hyvox reads");
    EXPECT_READ_ERROR(dir.write("noextension", "solid"), "its name has no extension");
    EXPECT_READ_ERROR(dir.write("scene.blend.gz", "x"), "'.blend' is not a format hyvox reads");
}

// Every cut and many byte changes of small valid files: a mesh whose indices are in range,
// or an InvalidInput; a cut never reads as a different mesh. The files' last value is one
// digit, so no cut can shorten a number into another valid file. The readers are given the
// bytes directly (readMesh reads a file into memory and hands it to them).
TEST(IoMeshFormats, EveryTruncationAndByteFlipIsReadOrRefused) {
    Triangles t = sample(5, 4, 9);
    t.triangles.back() = 4;
    using Reader = hyvox::Mesh (*)(const char*, std::size_t, const std::string&, hyvox::Interrupter*);
    const std::vector<std::tuple<std::string, std::string, Reader>> seeds = {
        {"b.stl", stlBinary(t), hyvox::mesh_io::readStl},
        {"a.stl", stlAscii(t), hyvox::mesh_io::readStl},
        {"o.off", off(t), hyvox::mesh_io::readOff}};
    std::mt19937 rng(6);
    const char interesting[] = {'\0', '\n', ' ', '-', '9', 'e', '#', '\xff', '\x7f', '3'};
    for (const auto& [name, bytes, reader] : seeds) {
        SCOPED_TRACE(name);
        std::size_t read = 0, refused = 0;
        const hyvox::Mesh whole = reader(bytes.data(), bytes.size(), name, nullptr);
        EXPECT_EQ(corners(whole), corners(t));
        const std::size_t last = bytes.find_last_not_of(" \n");
        for (std::size_t cut = 0; cut < bytes.size(); ++cut) {
            const std::vector<char> part(bytes.begin(), bytes.begin() + std::ptrdiff_t(cut));  // nothing past the cut
            try {
                const hyvox::Mesh mesh = reader(part.data(), part.size(), name, nullptr);
                // Only a cut in what follows the last value (a newline, an STL solid's name).
                EXPECT_EQ(corners(mesh), corners(whole)) << "cut at " << cut << " of " << bytes.size();
                EXPECT_TRUE(name == "a.stl" || cut > last) << "cut at " << cut;
                ++read;
            } catch (const hyvox::InvalidInput&) {
                ++refused;
            }
        }
        for (std::size_t i = 0; i < 16 * bytes.size(); ++i) {
            std::string changed = bytes;
            for (int n = 1 + int(rng() % 3); n > 0; --n)
                changed[rng() % changed.size()] = interesting[rng() % sizeof interesting];
            try {
                const hyvox::Mesh mesh = reader(changed.data(), changed.size(), name, nullptr);
                for (std::uint32_t index : mesh.triangles) ASSERT_LT(index, mesh.vertexCount()) << name;
                ++read;
            } catch (const hyvox::InvalidInput&) {
                ++refused;
            }
        }
        EXPECT_GT(read, 0u);
        EXPECT_GT(refused, 0u);
    }
}
