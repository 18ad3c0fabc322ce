// SPDX-License-Identifier: GPL-3.0-or-later
#include "support/test_mesh_loader.h"

#include <zlib.h>

#include <dirent.h>
#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <sstream>
#include <stdexcept>

namespace hyvox::test {
namespace {

struct GzCloser {
    void operator()(gzFile_s* f) const { gzclose(f); }
};

std::size_t sizeOfType(const std::string& type) {
    if (type == "float" || type == "float32" || type == "int" || type == "int32" || type == "uint" || type == "uint32")
        return 4;
    if (type == "uchar" || type == "uint8" || type == "char" || type == "int8") return 1;
    if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
    if (type == "double" || type == "float64") return 8;
    throw std::runtime_error("unsupported PLY type " + type);
}

bool endsWith(const std::string& s, const std::string& suffix) {
    return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

TestMesh loadTestMesh(const std::string& path) {
    // gzread reads plain files unchanged, so one path handles .ply and .ply.gz.
    std::unique_ptr<gzFile_s, GzCloser> file(gzopen(path.c_str(), "rb"));
    if (!file) throw std::runtime_error("cannot open " + path);
    gzbuffer(file.get(), 1 << 20);

    std::string header;
    while (header.size() < 65536) {
        const int c = gzgetc(file.get());
        if (c < 0) break;
        header.push_back(char(c));
        if (endsWith(header, "end_header\n")) break;
    }
    if (!endsWith(header, "end_header\n")) throw std::runtime_error("no PLY header in " + path);

    std::istringstream lines(header);
    std::string line, element;
    std::size_t vertices = 0, faces = 0, vertex_stride = 0;
    bool binary_le = false;
    while (std::getline(lines, line)) {
        std::istringstream words(line);
        std::string word;
        words >> word;
        if (word == "format") {
            std::string fmt;
            words >> fmt;
            binary_le = fmt == "binary_little_endian";
        } else if (word == "element") {
            std::size_t count = 0;
            words >> element >> count;
            if (element == "vertex") vertices = count;
            if (element == "face") faces = count;
        } else if (word == "property" && element == "vertex") {
            std::string type, name;
            words >> type >> name;
            // x, y, z must be the first three float properties.
            if (vertex_stride < 12 && type != "float") throw std::runtime_error("vertex x/y/z must be float");
            vertex_stride += sizeOfType(type);
        } else if (word == "property" && element == "face") {
            std::string list, count_type, index_type;
            words >> list >> count_type >> index_type;
            if (list != "list" || sizeOfType(count_type) != 1 || sizeOfType(index_type) != 4)
                throw std::runtime_error("faces must be 'list uchar int'");
        }
    }
    if (!binary_le || vertex_stride < 12) throw std::runtime_error("not a binary little-endian PLY: " + path);

    TestMesh mesh;
    mesh.name = path.substr(path.find_last_of('/') + 1);
    std::vector<unsigned char> vbytes(vertices * vertex_stride);
    if (gzread(file.get(), vbytes.data(), unsigned(vbytes.size())) != int(vbytes.size()))
        throw std::runtime_error("truncated vertex data in " + path);
    mesh.positions.resize(vertices * 3);
    for (std::size_t v = 0; v < vertices; ++v) std::memcpy(&mesh.positions[3 * v], &vbytes[v * vertex_stride], 12);

    std::vector<unsigned char> fbytes(faces * 13);
    if (gzread(file.get(), fbytes.data(), unsigned(fbytes.size())) != int(fbytes.size()))
        throw std::runtime_error("truncated face data in " + path);
    mesh.triangles.resize(faces * 3);
    for (std::size_t f = 0; f < faces; ++f) {
        if (fbytes[f * 13] != 3) throw std::runtime_error("a face is not a triangle in " + path);
        std::memcpy(&mesh.triangles[3 * f], &fbytes[f * 13 + 1], 12);
    }
    return mesh;
}

std::string meshDir() {
    const char* dir = std::getenv("HYVOX_MESH_DIR");
    return dir ? dir : "";
}

std::string meshPath(const std::string& file) { return meshDir() + "/" + file; }

std::vector<std::string> listMeshFiles() {
    std::vector<std::string> files;
    if (DIR* dir = opendir(meshDir().c_str())) {
        while (const dirent* entry = readdir(dir)) {
            const std::string name = entry->d_name;
            if (endsWith(name, ".ply") || endsWith(name, ".ply.gz")) files.push_back(name);
        }
        closedir(dir);
    }
    std::sort(files.begin(), files.end());
    return files;
}

const std::vector<std::string>& sharedMeshFiles() {
    static const std::vector<std::string> files = {
        "armadillo_52k.ply",
        "bunny_stanford_69k.ply",
        "dragon_stanford_871k.ply.gz",
        "dragon_stanford_res2_203k.ply.gz",
        "dragon_stanford_res3_48k.ply",
        "elephant_holes.ply",
        "happy_buddha_100k.ply",
        "igea_cyberware_268k.ply.gz",
        "shark_holes.ply",
        "spider_messy.ply",
        "sponza_crytek_262k_vcolor.ply.gz",
        "spot_uv.ply",
        "spot_vcolor.ply",
        "teapot_utah.ply",
    };
    return files;
}

std::string meshCaseName(const std::string& file, int resolution) {
    std::string name = file.substr(0, file.find('.')) + "_" + std::to_string(resolution);
    std::replace_if(name.begin(), name.end(), [](char c) { return !std::isalnum(static_cast<unsigned char>(c)); }, '_');
    return name;
}

}  // namespace hyvox::test
