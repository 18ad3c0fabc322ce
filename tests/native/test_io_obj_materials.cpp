// SPDX-License-Identifier: GPL-3.0-or-later
// OBJ materials (usemtl + MTL Kd / map_Kd): ids numbered by first use, colours and images
// found beside the files, and what cannot be used left out with a warning (never an error
// for the geometry); the MTL reader's own errors name the file and the line.
#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "hyvox/errors.h"
#include "hyvox/mesh_io.h"
#include "mesh_io/mtl_reader.h"
#include "support/temp_dir.h"

using hyvox::test::TempDir;

namespace {

const std::string kSquare = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";
const char kPng[] = "\x89PNG\r\n\x1a\n";  // the signature is what the reader checks

bool anyWarningHas(const hyvox::Mesh& mesh, const std::string& part) {
    for (const std::string& w : mesh.warnings)
        if (w.find(part) != std::string::npos) return true;
    return false;
}

}  // namespace

TEST(IoObjMaterials, IdsColoursAndImagesBesideTheFiles) {
    TempDir dir;
    std::filesystem::create_directories(dir.path / "tex");
    std::filesystem::create_directories(dir.path / "lib");
    dir.write("tex/a.png", std::string(kPng, 8));
    dir.write("lib/m.mtl", "newmtl red\nKd 1 0 0\nnewmtl painted\nKd 0.5\nmap_Kd ../tex/a.png\n");
    const hyvox::Mesh mesh = hyvox::readMesh(dir.write("m.obj",
                                                       "mtllib lib/m.mtl\n" + kSquare +
                                                           "f 1 2 3\nusemtl painted\nf 1 3 4\nusemtl red\nf 2 3 4\n"
                                                           "usemtl painted\nf 1 2 4\n")
                                                 .string());
    EXPECT_TRUE(mesh.warnings.empty());
    EXPECT_EQ(mesh.material_names, (std::vector<std::string>{"", "painted", "red"}));
    EXPECT_EQ(mesh.material_ids, (std::vector<std::uint32_t>{0, 1, 2, 1}));
    EXPECT_EQ(mesh.material_colors, (std::vector<float>{0.8f, 0.8f, 0.8f, 0.5f, 0.5f, 0.5f, 1, 0, 0}));
    ASSERT_EQ(mesh.material_textures.size(), 3u);
    EXPECT_EQ(mesh.material_textures[1], (dir.path / "lib/../tex/a.png").string());
    EXPECT_EQ(mesh.material_textures[0] + mesh.material_textures[2], "");
    const hyvox::MeshView view = mesh.view();
    EXPECT_EQ(view.palette_count, 3u);
    EXPECT_EQ(view.material_ids, mesh.material_ids.data());
}

TEST(IoObjMaterials, WhatCannotBeUsedIsAWarning) {
    TempDir dir;
    dir.write("not_png.png", "GIF89a");
    dir.write("m.mtl", "newmtl gone\nKd 0 1 0\nmap_Kd nowhere.png\nnewmtl gif\nmap_Kd not_png.png\n");
    const hyvox::Mesh mesh =
        hyvox::readMesh(dir.write("m.obj",
                                  "mtllib m.mtl absent.mtl\n" + kSquare +
                                      "usemtl gone\nf 1 2 3\nusemtl gif\nf 1 3 4\nusemtl unknown\nf 2 3 4\n")
                            .string());
    EXPECT_EQ(mesh.triangleCount(), 3u);
    EXPECT_TRUE(anyWarningHas(mesh, "absent.mtl")) << mesh.warnings.size();
    EXPECT_TRUE(anyWarningHas(mesh, "nowhere.png"));
    EXPECT_TRUE(anyWarningHas(mesh, "is not a PNG"));
    EXPECT_TRUE(anyWarningHas(mesh, "'unknown'"));
    EXPECT_EQ(mesh.material_textures, (std::vector<std::string>{"", "", ""}));
    EXPECT_EQ(mesh.material_colors, (std::vector<float>{0, 1, 0, 0.8f, 0.8f, 0.8f, 0.8f, 0.8f, 0.8f}));
}

TEST(IoObjMaterials, AFileWithoutUsemtlHasNoMaterials) {
    TempDir dir;
    const hyvox::Mesh mesh = hyvox::readMesh(dir.write("m.obj", "mtllib m.mtl\n" + kSquare + "f 1 2 3\n").string());
    EXPECT_FALSE(mesh.hasMaterials());
    EXPECT_TRUE(mesh.material_names.empty());
    EXPECT_EQ(mesh.view().material_ids, nullptr);
}

TEST(IoObjMaterials, MtlErrorsNameTheFileAndLine) {
    auto errorOf = [](const std::string& text) {
        try {
            hyvox::mesh_io::readMtl(text.data(), text.size(), "m.mtl");
        } catch (const hyvox::InvalidInput& e) {
            return std::string(e.what());
        }
        return std::string("(no error)");
    };
    EXPECT_NE(errorOf("Kd 1 1 1\n").find("line 1: 'Kd' comes before any 'newmtl'"), std::string::npos);
    EXPECT_NE(errorOf("newmtl a\nKd 1 x 1\n").find("line 2: 'x' is not a number"), std::string::npos);
    EXPECT_NE(errorOf("newmtl a\nKd 1 1\n").find("2 numbers"), std::string::npos);
    EXPECT_NE(errorOf("newmtl a\nKd nan 1 1\n").find("m.mtl"), std::string::npos);
    EXPECT_NE(errorOf("newmtl\n").find("needs a material name"), std::string::npos);
    EXPECT_NE(errorOf("newmtl a\nmap_Kd\n").find("needs a file name"), std::string::npos);
    const std::string good = "newmtl a b\nKd 0.5\nmap_Kd -bm 1 -s 2 2 2 dir\\t.png\nnewmtl c\nmap_Kd my file.png\n";
    const auto materials = hyvox::mesh_io::readMtl(good.data(), good.size(), "m.mtl");
    ASSERT_EQ(materials.size(), 2u);
    EXPECT_EQ(materials[0].name, "a b");
    EXPECT_EQ(*materials[0].diffuse, (std::array<float, 3>{0.5f, 0.5f, 0.5f}));
    EXPECT_EQ(materials[0].diffuse_map, "dir/t.png");
    EXPECT_FALSE(materials[1].diffuse);
    EXPECT_EQ(materials[1].diffuse_map, "my file.png");
}
