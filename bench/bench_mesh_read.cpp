// SPDX-License-Identifier: GPL-3.0-or-later
// Mesh reading time: hyvox::readMesh (its strict readers, or assimp in its own process for
// the formats read through assimp) against assimp in this process (support/assimp_mesh.h:
// the path hyvox took before), median of --repeat runs each.
//   bench_mesh_read [--repeat N] [--json FILE] MESH...
// --json: the rows also as a JSON list (bench/bench_mesh_formats.py drives it).
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "bench_args.h"
#include "hyvox/mesh_io.h"
#include "support/assimp_mesh.h"

namespace {

template <typename Read>
double medianMs(int repeat, Read read, std::size_t& triangles) {
    std::vector<double> ms;
    for (int r = 0; r < repeat; ++r) {
        const auto start = std::chrono::steady_clock::now();
        const hyvox::Mesh mesh = read();
        ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
        triangles = mesh.triangleCount();
    }
    return hyvox::bench::median(ms);
}

}  // namespace

int main(int argc, char** argv) {
    int repeat = 5;
    std::string json_path;
    std::vector<std::string> files;
    for (int a = 1; a < argc; ++a) {
        const std::string arg = argv[a];
        if (arg == "--repeat")
            repeat = std::max(1, std::atoi(hyvox::bench::optionValue(argc, argv, a).c_str()));
        else if (arg == "--json")
            json_path = hyvox::bench::optionValue(argc, argv, a);
        else
            files.push_back(arg);
    }
    std::string json = "[";
    if (files.empty()) {
        std::fprintf(stderr, "usage: bench_mesh_read [--repeat N] MESH...\n");
        return 2;
    }
    std::printf("%-40s %10s %12s %12s %8s\n", "mesh", "triangles", "assimp ms", "hyvox ms", "speed-up");
    for (const std::string& file : files) {
        std::size_t old_triangles = 0, new_triangles = 0;
        const double old_ms = medianMs(repeat, [&] { return hyvox::test::readMeshWithAssimp(file); }, old_triangles);
        const double new_ms = medianMs(repeat, [&] { return hyvox::readMesh(file); }, new_triangles);
        const std::string name = file.substr(file.find_last_of('/') + 1);
        std::printf("%-40s %10zu %12.1f %12.1f %7.1fx%s\n", name.c_str(), new_triangles, old_ms, new_ms, old_ms / new_ms,
                    old_triangles == new_triangles ? "" : "  (triangle counts differ!)");
        char row[512];
        std::snprintf(row, sizeof row, "%s{\"file\": \"%s\", \"triangles\": %zu, \"assimp_triangles\": %zu, "
                      "\"assimp_ms\": %.3f, \"hyvox_ms\": %.3f}", json.size() > 1 ? ", " : "", name.c_str(),
                      new_triangles, old_triangles, old_ms, new_ms);
        json += row;
    }
    if (!json_path.empty()) {
        std::FILE* out = std::fopen(json_path.c_str(), "w");
        if (!out) return 1;
        std::fprintf(out, "%s]\n", json.c_str());
        std::fclose(out);
    }
    return 0;
}
