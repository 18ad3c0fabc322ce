// SPDX-License-Identifier: GPL-3.0-or-later
// Mesh reading time: hyvox::readMesh (its strict readers, or assimp in its own process for
// the formats read through assimp) against assimp in this process (support/assimp_mesh.h:
// the path hyvox took before), median of --repeat runs each.
//   bench_mesh_read [--repeat N] [--out DIR] [--json FILE] MESH...
// The table also goes to DIR/mesh_read.{json,md} (default bench/results/); --json: the rows
// also as a plain JSON list (bench/bench_mesh_formats.py drives it).
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "bench_args.h"
#include "bench_results.h"
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
    std::string out_dir = HYVOX_BENCH_RESULTS_DIR;
    for (int a = 1; a < argc; ++a) {
        const std::string arg = argv[a];
        if (arg == "--repeat")
            repeat = std::max(1, std::atoi(hyvox::bench::optionValue(argc, argv, a).c_str()));
        else if (arg == "--out")
            out_dir = hyvox::bench::optionValue(argc, argv, a);
        else if (arg == "--json")
            json_path = hyvox::bench::optionValue(argc, argv, a);
        else
            files.push_back(arg);
    }
    std::string json = "[";
    if (files.empty()) {
        std::fprintf(stderr, "usage: bench_mesh_read [--repeat N] [--out DIR] [--json FILE] MESH...\n");
        return 2;
    }
    std::printf("%-40s %10s %12s %12s %8s\n", "mesh", "triangles", "assimp ms", "hyvox ms", "speed-up");
    hyvox::bench::ResultTable table("mesh_read", "Mesh reading: hyvox's readers against assimp in the process",
                                    {{"mesh"}, {"triangles"}, {"assimp ms", 1}, {"hyvox ms", 1}, {"assimp / hyvox", 1}},
                                    argc, argv);
    table.note("Medians of " + std::to_string(repeat) + " reads of each file, one after the other.");
    for (const std::string& file : files) {
        std::size_t old_triangles = 0, new_triangles = 0;
        const double old_ms = medianMs(repeat, [&] { return hyvox::test::readMeshWithAssimp(file); }, old_triangles);
        const double new_ms = medianMs(repeat, [&] { return hyvox::readMesh(file); }, new_triangles);
        const std::string name = file.substr(file.find_last_of('/') + 1);
        std::printf("%-40s %10zu %12.1f %12.1f %7.1fx%s\n", name.c_str(), new_triangles, old_ms, new_ms,
                    old_ms / new_ms, old_triangles == new_triangles ? "" : "  (triangle counts differ!)");
        if (old_triangles != new_triangles) table.note(name + ": the two readers give different triangle counts");
        table.add({name, new_triangles, old_ms, new_ms, old_ms / new_ms});
        char row[512];
        std::snprintf(row, sizeof row,
                      "%s{\"file\": \"%s\", \"triangles\": %zu, \"assimp_triangles\": %zu, "
                      "\"assimp_ms\": %.3f, \"hyvox_ms\": %.3f}",
                      json.size() > 1 ? ", " : "", name.c_str(), new_triangles, old_triangles, old_ms, new_ms);
        json += row;
    }
    if (!json_path.empty()) {
        std::FILE* out = std::fopen(json_path.c_str(), "w");
        if (!out) return 1;
        std::fprintf(out, "%s]\n", json.c_str());
        std::fclose(out);
    }
    table.write(out_dir);
    return 0;
}
