// SPDX-License-Identifier: GPL-3.0-or-later
#include "voxelize_command.h"

#include <tbb/global_control.h>

#include <chrono>
#include <memory>
#include <cstdio>
#include <filesystem>
#include <string>

#include "hyvox/hyvox.h"
#include "hyvox/mesh_io.h"
#include "hyvox/stats_json.h"
#include "hyvox/vdb.h"
#include "hyvox/version.h"

namespace hyvox::cli {
namespace {

class StopFlagInterrupter final : public Interrupter {
public:
    explicit StopFlagInterrupter(const std::atomic<bool>& stop) : stop_(stop) {}
    bool wasInterrupted(int) override { return stop_.load(std::memory_order_relaxed); }

private:
    const std::atomic<bool>& stop_;
};

// Fails before the (possibly long) voxelization when an output could not be written anyway.
// The writers still check everything themselves; this only saves the wait.
void checkOutputFolder(const std::string& path, const char* what) {
    namespace fs = std::filesystem;
    std::error_code error;
    if (fs::is_directory(fs::path(path), error))
        throw InvalidInput(std::string("cannot write ") + what + " '" + path + "': it is a folder");
    fs::path folder = fs::path(path).parent_path();
    if (folder.empty()) folder = ".";
    if (!fs::is_directory(folder, error))
        throw InvalidInput(std::string("cannot write ") + what + " '" + path + "': folder '" + folder.string() +
                           "' does not exist");
}

double msSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

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
    double total = 0;
    for (const auto& [stage, ms] : s.timings_ms) {
        std::printf(" %s %.1f,", stage.c_str(), ms);
        total += ms;
    }
    std::printf(" total %.1f\n", total);
}

}  // namespace

void runVoxelize(const Arguments& args, const std::atomic<bool>& stop) {
    // --threads bounds the whole run (the .vdb tree is also built in parallel), not only the backend.
    std::unique_ptr<tbb::global_control> thread_limit;
    if (args.options.threads > 0)
        thread_limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                             std::size_t(args.options.threads));
    checkOutputFolder(args.output_path, "the output");
    if (!args.stats_json_path.empty()) checkOutputFolder(args.stats_json_path, "the stats");
    auto start = std::chrono::steady_clock::now();
    const Mesh mesh = readMesh(args.mesh_path);
    const double read_ms = msSince(start);
    if (stop.load()) throw Cancelled();

    StopFlagInterrupter interrupter(stop);
    VoxelizeResult result = voxelize(mesh.view(), args.options, &interrupter);
    result.stats.timings_ms.insert(result.stats.timings_ms.begin(), {"read_mesh", read_ms});

    if (stop.load()) throw Cancelled();
    start = std::chrono::steady_clock::now();
    writeVdb(result, args.output_path);
    result.stats.addTiming("write_vdb", msSince(start));

    if (!args.stats_json_path.empty()) writeTextFileAtomic(args.stats_json_path, statsToJson(result));
    if (!args.quiet) printSummary(args, mesh, result);
}

}  // namespace hyvox::cli
