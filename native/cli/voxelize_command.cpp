// SPDX-License-Identifier: GPL-3.0-or-later
#include "voxelize_command.h"

#include <chrono>
#include <cstdio>
#include <future>
#include <string>

#include "command_support.h"
#include "hyvox/hyvox.h"
#include "hyvox/mesh_io.h"
#include "hyvox/stats_json.h"
#include "hyvox/texture.h"
#include "hyvox/vdb.h"
#include "hyvox/version.h"
#include "progress_line.h"

namespace hyvox::cli {
namespace {

void printSummary(const Arguments& args, const Mesh& mesh, const VoxelizeResult& r) {
    const Stats& s = r.stats;
    const GridSpec& g = r.grid;
    std::printf("hyvox %s: %s -> %s\n", version(), args.mesh_path.c_str(), args.output_path.c_str());
    std::printf("  mesh     %zu vertices, %llu triangles (%llu used, %llu degenerate skipped)\n", mesh.vertexCount(),
                (unsigned long long)s.triangles_input, (unsigned long long)s.triangles_used,
                (unsigned long long)s.triangles_degenerate);
    std::printf("  grid     %d x %d x %d voxels of %.6g, origin (%.6g, %.6g, %.6g)\n", g.dims[0], g.dims[1], g.dims[2],
                g.voxel_size, g.origin[0], g.origin[1], g.origin[2]);
    std::printf("  voxels   %llu occupied (%s, %s)\n", (unsigned long long)s.voxel_count, s.mode.c_str(),
                s.method.c_str());
    std::printf("  time ms ");
    for (const auto& [stage, ms] : s.timings_ms) std::printf(" %s %.1f,", stage.c_str(), ms);
    std::printf(" total %.1f\n", s.totalMs());
}

}  // namespace

void runVoxelize(const Arguments& args, const std::atomic<bool>& stop) {
    const auto thread_limit = limitThreads(args.options.threads);
    checkOutputPaths(args.mesh_path, args.output_path, args.stats_json_path);
    ProgressLine interrupter = progressFor(args, stop);  // Ctrl-C stops the reading too
    // The mesh is read on a thread of its own while this one sets up TBB's thread pool
    // (command_support.h); an error in the file is rethrown here by get().
    double read_ms = 0;
    std::future<Mesh> reading = std::async(std::launch::async, [&] {
        const auto start = std::chrono::steady_clock::now();
        Mesh read = readMesh(args.mesh_path, &interrupter, meshReadOptions(args));
        read_ms = msSince(start);
        return read;
    });
    initializeThreadPool();
    const Mesh mesh = reading.get();
    for (const std::string& warning : mesh.warnings) std::fprintf(stderr, "hyvox: warning: %s\n", warning.c_str());

    MeshView view = mesh.view();
    Texture texture;
    if (!args.texture_path.empty()) {
        texture = readPngTexture(args.texture_path);
        view.texture = &texture;
    }
    // The materials' images (OBJ map_Kd), decoded only when colour is asked for.
    MaterialTextures material_textures;
    if (mesh.hasMaterials() && args.options.attributes.color) {
        material_textures = readMaterialTextures(mesh.material_textures);
        view.material_textures = material_textures.of_material.data();
    }
    // The output is always a .vdb: a voxel size it cannot hold is refused before the work.
    const auto start = std::chrono::steady_clock::now();
    const ValidatedMesh validated = validate(view, args.options, &interrupter);
    const double validate_ms = msSince(start);
    checkVdbVoxelSize(makeGrid(validated.bounds, args.options.grid).voxel_size);
    VoxelizeResult result = voxelize(validated, args.options, &interrupter, validate_ms);
    result.stats.timings_ms.insert(result.stats.timings_ms.begin(), {"read_mesh", read_ms});

    if (stop.load()) throw Cancelled();
    const VdbWriteReport written = writeVdb(result, args.output_path, args.write, &interrupter);
    result.stats.addTiming("build_vdb", written.build_ms);
    result.stats.addTiming("write_vdb", written.write_ms);
    result.stats.vdb_bytes = written.grid_bytes;

    if (!args.stats_json_path.empty())
        writeTextFileAtomic(args.stats_json_path, statsToJson(result), args.write.durable);
    if (!args.quiet) printSummary(args, mesh, result);
}

}  // namespace hyvox::cli
