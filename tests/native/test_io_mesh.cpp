// SPDX-License-Identifier: GPL-3.0-or-later
// Mesh reading: the shared meshes' counts from their README, exact values against a raw
// parse of the binary PLY, ascii PLY / OBJ / .ply.gz written here, and clear errors.
#include <gtest/gtest.h>
#include <zlib.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "hyvox/errors.h"
#include "hyvox/mesh_io.h"
#include "support/temp_dir.h"

namespace fs = std::filesystem;

namespace {

fs::path meshDir() {
    const char* dir = std::getenv("HYVOX_MESH_DIR");
    return dir ? fs::path(dir) : fs::path();
}

using hyvox::test::TempDir;

struct SharedMesh {
    const char* file;
    std::size_t triangles;
    std::size_t vertices;
    bool colors;
    bool uvs;
};

// From ../shared/data/meshes/README.md.
const SharedMesh kSharedMeshes[] = {
    {"bunny_stanford_69k.ply", 69451, 35947, false, false},
    {"dragon_stanford_871k.ply.gz", 871414, 437645, false, false},
    {"dragon_stanford_res2_203k.ply.gz", 202520, 100250, false, false},
    {"dragon_stanford_res3_48k.ply", 47794, 22998, false, false},
    {"happy_buddha_100k.ply", 100000, 49990, false, false},
    {"armadillo_52k.ply", 52000, 26002, false, false},
    {"igea_cyberware_268k.ply.gz", 268686, 134345, false, false},
    {"sponza_crytek_262k_vcolor.ply.gz", 262267, 145050, true, false},
    {"teapot_utah.ply", 992, 792, false, false},
    {"spot_uv.ply", 5856, 3225, false, true},
    {"spot_vcolor.ply", 5856, 2930, true, false},
    {"spider_messy.ply", 1368, 762, false, false},
    {"shark_holes.ply", 10192, 5246, false, false},
    {"elephant_holes.ply", 4463, 2798, false, false},
};

const std::string kAsciiPly =
    "ply\n"
    "format ascii 1.0\n"
    "comment a tetrahedron plus a degenerate and a duplicate triangle\n"
    "element vertex 4\n"
    "property float x\n"
    "property float y\n"
    "property float z\n"
    "element face 6\n"
    "property list uchar int vertex_indices\n"
    "end_header\n"
    "0 0 0\n"
    "1.5 0 0\n"
    "0 2.25 0\n"
    "0 0 -3.125\n"
    "3 0 2 1\n"
    "3 0 1 3\n"
    "3 0 3 2\n"
    "3 1 2 3\n"
    "3 1 1 2\n"
    "3 0 1 3\n";

void expectTetrahedron(const hyvox::Mesh& mesh) {
    ASSERT_EQ(mesh.vertexCount(), 4u);
    ASSERT_EQ(mesh.triangleCount(), 6u);  // the degenerate and the duplicate stay
    EXPECT_EQ(mesh.positions, (std::vector<float>{0, 0, 0, 1.5f, 0, 0, 0, 2.25f, 0, 0, 0, -3.125f}));
    EXPECT_EQ(mesh.triangles, (std::vector<std::uint32_t>{0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3, 1, 1, 2, 0, 1, 3}));
    const hyvox::MeshView view = mesh.view();
    EXPECT_EQ(view.vertex_count, 4u);
    EXPECT_EQ(view.triangle_count, 6u);
    EXPECT_EQ(view.positions, mesh.positions.data());
}

}  // namespace

TEST(IoMesh, SharedMeshesHaveTheirReadmeCounts) {
    ASSERT_FALSE(meshDir().empty()) << "HYVOX_MESH_DIR is not set (CTest sets it); a skip would hide the check";
    for (const SharedMesh& m : kSharedMeshes) {
        SCOPED_TRACE(m.file);
        const hyvox::Mesh mesh = hyvox::readMesh((meshDir() / m.file).string());
        EXPECT_EQ(mesh.triangleCount(), m.triangles);
        EXPECT_EQ(mesh.vertexCount(), m.vertices);
        EXPECT_EQ(mesh.hasColors(), m.colors);
        EXPECT_EQ(mesh.hasUvs(), m.uvs);
        if (m.colors) {
            EXPECT_EQ(mesh.colors.size(), 4 * m.vertices);
        }
        if (m.uvs) {
            EXPECT_EQ(mesh.uvs.size(), 2 * m.vertices);
        }
    }
}

TEST(IoMesh, BinaryPlyValuesMatchTheFileBytes) {
    // The README's layout: a header, then float xyz per vertex, then 13-byte faces
    // (uchar 3 + three int32). Reading the bytes ourselves shows nothing was reordered.
    ASSERT_FALSE(meshDir().empty()) << "HYVOX_MESH_DIR is not set (CTest sets it); a skip would hide the check";
    const fs::path path = meshDir() / "spider_messy.ply";
    std::ifstream in(path, std::ios::binary);
    std::string line;
    std::size_t vertices = 0, faces = 0;
    while (std::getline(in, line) && line != "end_header") {
        std::sscanf(line.c_str(), "element vertex %zu", &vertices);
        std::sscanf(line.c_str(), "element face %zu", &faces);
    }
    std::vector<float> positions(3 * vertices);
    in.read(reinterpret_cast<char*>(positions.data()), std::streamsize(positions.size() * sizeof(float)));
    std::vector<std::uint32_t> triangles;
    for (std::size_t f = 0; f < faces; ++f) {
        char record[13];
        in.read(record, 13);
        ASSERT_EQ(record[0], 3);
        std::int32_t idx[3];
        std::memcpy(idx, record + 1, 12);
        triangles.insert(triangles.end(), {std::uint32_t(idx[0]), std::uint32_t(idx[1]), std::uint32_t(idx[2])});
    }
    ASSERT_TRUE(in) << "short file";
    const hyvox::Mesh mesh = hyvox::readMesh(path.string());
    EXPECT_EQ(mesh.positions, positions);
    EXPECT_EQ(mesh.triangles, triangles);
}

TEST(IoMesh, AsciiPlyKeepsDegenerateAndDuplicateTriangles) {
    TempDir dir;
    expectTetrahedron(hyvox::readMesh(dir.write("tet.ply", kAsciiPly).string()));
}

TEST(IoMesh, GzippedPly) {
    TempDir dir;
    const fs::path path = dir.path / "tet.ply.gz";
    gzFile gz = gzopen(path.c_str(), "wb");
    ASSERT_NE(gz, nullptr);
    ASSERT_EQ(gzwrite(gz, kAsciiPly.data(), unsigned(kAsciiPly.size())), int(kAsciiPly.size()));
    gzclose(gz);
    expectTetrahedron(hyvox::readMesh(path.string()));
}

TEST(IoMesh, ObjKeepsTrianglesAndSharedVertices) {
    TempDir dir;
    const fs::path path = dir.write("quad.obj",
                                    "# a quad (split in two), a degenerate and a duplicate triangle\n"
                                    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 0.5 2\n"
                                    "f 1 2 3 4\n"
                                    "f 1 1 5\n"
                                    "f 1 2 5\n"
                                    "f 1 2 5\n");
    const hyvox::Mesh mesh = hyvox::readMesh(path.string());
    EXPECT_EQ(mesh.triangleCount(), 5u);
    EXPECT_EQ(mesh.vertexCount(), 5u);  // corners welded back to the file's vertices
    // Every triangle's corners are the file's positions.
    const float file_positions[5][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5f, 0.5f, 2}};
    const int expected_corners[5][3] = {{0, 1, 2}, {0, 2, 3}, {0, 0, 4}, {0, 1, 4}, {0, 1, 4}};
    for (std::size_t t = 0; t < 5; ++t)
        for (int c = 0; c < 3; ++c) {
            const std::uint32_t v = mesh.triangles[3 * t + c];
            const int f = expected_corners[t][c];
            for (int a = 0; a < 3; ++a) EXPECT_EQ(mesh.positions[3 * v + a], file_positions[f][a]) << t << " " << c;
        }
    // The degenerate triangle still repeats a vertex.
    EXPECT_EQ(mesh.triangles[6], mesh.triangles[7]);
}

TEST(IoMesh, StlSoupIsWelded) {
    TempDir dir;
    const fs::path path = dir.write("two.stl",
                                    "solid two\n"
                                    "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\n"
                                    "endloop\nendfacet\n"
                                    "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 1 0\nvertex 0 1 0\n"
                                    "endloop\nendfacet\n"
                                    "endsolid two\n");
    const hyvox::Mesh mesh = hyvox::readMesh(path.string());
    EXPECT_EQ(mesh.triangleCount(), 2u);
    EXPECT_EQ(mesh.vertexCount(), 4u);
    EXPECT_EQ(mesh.triangles[0], mesh.triangles[3]);  // the shared corners are one vertex
    EXPECT_EQ(mesh.triangles[2], mesh.triangles[4]);
}

TEST(IoMesh, ClearErrors) {
    TempDir dir;
    auto message = [](const std::string& path) -> std::string {
        try {
            hyvox::readMesh(path);
        } catch (const hyvox::InvalidInput& e) {
            return e.what();
        }
        return "(no error)";
    };
    const std::string missing = (dir.path / "missing.ply").string();
    EXPECT_NE(message(missing).find("missing.ply"), std::string::npos) << message(missing);
    EXPECT_NE(message(missing).find("No such file"), std::string::npos) << message(missing);
    EXPECT_NE(message(dir.path.string()).find("folder"), std::string::npos);
    EXPECT_NE(message(dir.write("empty.ply", "").string()).find("empty"), std::string::npos);
    EXPECT_NE(message(dir.write("junk.ply", "this is not a mesh\n").string()).find("junk.ply"), std::string::npos);
    EXPECT_NE(message(dir.write("junk.ply.gz", "not gzip either").string()).find("junk.ply.gz"), std::string::npos);
    EXPECT_NE(message(dir.write("points.obj", "v 0 0 0\nv 1 0 0\n").string()).find("points.obj"), std::string::npos);
}
