// SPDX-License-Identifier: GPL-3.0-or-later
// hyvox `cpu` against OpenVDB's tools::meshToUnsignedDistanceField with a 1-voxel band
// (what Blender's Mesh to Volume uses), same voxel size, same process, same threads.
//
//   bench_mesh_to_volume [--runs R] [--res N]... [--mesh-dir DIR] [--out DIR] [MESH...]
//
// Defaults: the bunny, the 871k dragon and Sponza from the shared meshes, at 256 and 512,
// median of 5 runs. Prints a table and writes it to DIR/mesh_to_volume.{json,md} (default
// bench/results/).
// Times, per case (medians, milliseconds):
//   stage   hyvox's "voxelize" stage alone (the backend: what the goals measure)
//   call    the whole hyvox::voxelize() call (validate, allocate, voxelize, count)
//   +vdb    call plus building the OpenVDB density grid from the bits (a fair match for
//           OpenVDB's output, which is a grid)
//   openvdb meshToUnsignedDistanceField (input arrays prepared beforehand, not timed)
// Peak RSS: each side runs in its own forked child; the figure is its high-water mark above
// the resident set it started with (the meshes), so the two sides are measured apart.
#include <openvdb/tools/MeshToVolume.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "bench_args.h"
#include "bench_results.h"
#include "core/stopwatch.h"
#include "hyvox/hyvox.h"
#include "hyvox/mesh_io.h"
#include "hyvox/version.h"
#include "openvdb_arrays.h"
#include "vdb/vdb_grid.h"

namespace {

using hyvox::bench::median;

// kB fields of /proc/self/status (VmRSS, VmHWM).
long statusKb(const char* field) {
    std::ifstream status("/proc/self/status");
    std::string line;
    const std::string key = std::string(field) + ":";
    while (std::getline(status, line))
        if (line.compare(0, key.size(), key) == 0) return std::atol(line.c_str() + key.size());
    return -1;
}

// What one side of a case measured, passed from a child process through a pipe.
struct Measured {
    double stage_ms = 0, call_ms = 0, with_vdb_ms = 0, openvdb_ms = 0, voxel_size = 0;
    std::uint64_t voxels = 0;
    double peak_mib = 0;  // peak RSS above the RSS the child started with
    char error[200] = {};
};

// Runs `work` in a forked child, so each side starts from the same heap (the parent has only
// read meshes, and has never started TBB threads, which do not survive fork) and its peak RSS
// is its own: the high-water mark is reset (/proc/self/clear_refs, Linux >= 4.0) at the start.
Measured inChild(const std::function<Measured()>& work) {
    int fds[2];
    if (::pipe(fds) != 0) throw std::runtime_error("pipe failed");
    const pid_t pid = ::fork();
    if (pid < 0) throw std::runtime_error("fork failed");
    if (pid == 0) {
        ::close(fds[0]);
        std::ofstream("/proc/self/clear_refs") << "5";
        const long base_kb = statusKb("VmRSS");
        Measured m;
        try {
            m = work();
        } catch (const std::exception& e) {
            std::snprintf(m.error, sizeof m.error, "%s", e.what());
        }
        m.peak_mib = double(statusKb("VmHWM") - base_kb) / 1024.0;
        const bool ok = ::write(fds[1], &m, sizeof m) == ssize_t(sizeof m);
        ::_exit(ok ? 0 : 1);
    }
    ::close(fds[1]);
    Measured m;
    const ssize_t got = ::read(fds[0], &m, sizeof m);
    ::close(fds[0]);
    int status = 0;
    ::waitpid(pid, &status, 0);
    if (got != ssize_t(sizeof m)) throw std::runtime_error("benchmark child process failed");
    if (m.error[0]) throw std::runtime_error(m.error);
    return m;
}

struct Row {
    std::string mesh;
    int resolution = 0;
    std::size_t triangles = 0;
    double voxel_size = 0;
    std::uint64_t hyvox_voxels = 0;
    std::uint64_t openvdb_voxels = 0;
    double stage_ms = 0, call_ms = 0, with_vdb_ms = 0, openvdb_ms = 0;
    double hyvox_peak_mib = 0, openvdb_peak_mib = 0;
};

Row runCase(const std::string& name, const hyvox::Mesh& mesh, int resolution, int runs) {
    Row row;
    row.mesh = name;
    row.resolution = resolution;
    row.triangles = mesh.triangleCount();

    const Measured ours = inChild([&] {
        hyvox::VoxelizeOptions options;
        options.grid.resolution = resolution;
        options.method = hyvox::Method::Cpu;
        std::vector<double> stage, call, with_vdb;
        Measured m;
        for (int r = 0; r < runs; ++r) {
            hyvox::Stopwatch watch;
            hyvox::VoxelizeResult result = hyvox::voxelize(mesh.view(), options);
            call.push_back(watch.elapsedMs());
            auto vdb = hyvox::vdb::makeDensityGrid(result.grid, result.occupancy);
            with_vdb.push_back(watch.elapsedMs());
            stage.push_back(result.stats.timingMs("voxelize"));
            m.voxels = result.stats.voxel_count;
            m.voxel_size = result.grid.voxel_size;
        }
        m.stage_ms = median(stage);
        m.call_ms = median(call);
        m.with_vdb_ms = median(with_vdb);
        return m;
    });
    row.stage_ms = ours.stage_ms;
    row.call_ms = ours.call_ms;
    row.with_vdb_ms = ours.with_vdb_ms;
    row.hyvox_voxels = ours.voxels;
    row.hyvox_peak_mib = ours.peak_mib;
    row.voxel_size = ours.voxel_size;

    // The same grid as hyvox's (no TBB in this process: makeGrid is plain code).
    const hyvox::ValidatedMesh validated = hyvox::validate(mesh.view());
    hyvox::GridOptions grid_options;
    grid_options.resolution = resolution;
    const hyvox::GridSpec grid = hyvox::makeGrid(validated.bounds, grid_options);

    const Measured theirs = inChild([&] {
        // OpenVDB's input: its own point/triangle arrays, made before timing.
        const hyvox::bench::OpenVdbArrays arrays = hyvox::bench::openvdbArrays(mesh);
        const std::vector<openvdb::Vec3s>& points = arrays.points;
        const std::vector<openvdb::Vec3I>& triangles = arrays.triangles;
        const std::vector<openvdb::Vec4I> quads;
        const auto transform = hyvox::vdb::makeTransform(grid);  // same voxels as hyvox's grid
        std::vector<double> times;
        Measured m;
        for (int r = 0; r < runs; ++r) {
            hyvox::Stopwatch watch;
            auto udf = openvdb::tools::meshToUnsignedDistanceField<openvdb::FloatGrid>(*transform, points, triangles,
                                                                                       quads, 1.0f);
            times.push_back(watch.elapsedMs());
            m.voxels = udf->activeVoxelCount();
        }
        m.openvdb_ms = median(times);
        return m;
    });
    row.openvdb_ms = theirs.openvdb_ms;
    row.openvdb_voxels = theirs.voxels;
    row.openvdb_peak_mib = theirs.peak_mib;
    return row;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        int runs = 5;
        std::vector<int> resolutions;
        std::vector<std::string> meshes;
        const char* env_dir = std::getenv("HYVOX_MESH_DIR");
        std::string mesh_dir = env_dir ? env_dir : HYVOX_BENCH_MESH_DIR;
        std::string out_dir = HYVOX_BENCH_RESULTS_DIR;
        for (int a = 1; a < argc; ++a) {
            const std::string arg = argv[a];
            auto value = [&] { return hyvox::bench::optionValue(argc, argv, a); };
            if (arg == "--runs")
                runs = std::max(1, std::atoi(value().c_str()));
            else if (arg == "--res")
                resolutions.push_back(std::atoi(value().c_str()));
            else if (arg == "--mesh-dir")
                mesh_dir = value();
            else if (arg == "--out")
                out_dir = value();
            else if (arg == "-h" || arg == "--help") {
                std::puts("bench_mesh_to_volume [--runs R] [--res N]... [--mesh-dir DIR] [--out DIR] [MESH...]");
                return 0;
            } else
                meshes.push_back(arg);
        }
        if (resolutions.empty()) resolutions = {256, 512};
        if (meshes.empty())
            meshes = {"bunny_stanford_69k.ply", "dragon_stanford_871k.ply.gz", "sponza_crytek_262k_vcolor.ply.gz"};
        hyvox::vdb::initializeOpenVdb();

        std::printf(
            "hyvox %s cpu vs OpenVDB %s meshToUnsignedDistanceField (band 1 voxel); median of %d runs, "
            "%u hardware threads\n\n",
            hyvox::version(), openvdb::getLibraryAbiVersionString(), runs, std::thread::hardware_concurrency());
        std::printf("%-34s %5s %9s %9s %8s %8s %8s %9s %7s %7s %9s %9s\n", "mesh", "res", "hyvox vox", "vdb vox",
                    "stage", "call", "+vdb", "openvdb", "x call", "x +vdb", "RSS hyvox", "RSS vdb");
        hyvox::bench::ResultTable table("mesh_to_volume",
                                        "The surface: hyvox cpu against OpenVDB meshToUnsignedDistanceField",
                                        {{"mesh"},
                                         {"res"},
                                         {"triangles"},
                                         {"hyvox voxels"},
                                         {"OpenVDB voxels"},
                                         {"stage ms", 1},
                                         {"call ms", 1},
                                         {"call + vdb ms", 1},
                                         {"OpenVDB ms", 1},
                                         {"OpenVDB / call", 1},
                                         {"OpenVDB / call + vdb", 1},
                                         {"hyvox peak MiB", 0},
                                         {"OpenVDB peak MiB", 0}},
                                        argc, argv);
        table.note("Medians of " + std::to_string(runs) +
                   " runs, all cores. stage: the voxelize stage; call: the whole hyvox::voxelize() call; "
                   "+ vdb: with the OpenVDB density grid built from it; OpenVDB: meshToUnsignedDistanceField, "
                   "1-voxel band, same voxel size; peak: resident memory each side adds (own process).");
        for (const std::string& name : meshes) {
            const std::string path = name.find('/') == std::string::npos ? mesh_dir + "/" + name : name;
            const hyvox::Mesh mesh = hyvox::readMesh(path);
            const std::string label = std::filesystem::path(path).filename().string();
            for (int res : resolutions) {
                const Row row = runCase(label, mesh, res, runs);
                table.add({row.mesh, row.resolution, row.triangles, row.hyvox_voxels, row.openvdb_voxels, row.stage_ms,
                           row.call_ms, row.with_vdb_ms, row.openvdb_ms, row.openvdb_ms / row.call_ms,
                           row.openvdb_ms / row.with_vdb_ms, row.hyvox_peak_mib, row.openvdb_peak_mib});
                std::printf("%-34s %5d %9llu %9llu %8.1f %8.1f %8.1f %9.1f %6.1fx %6.1fx %6.1f MiB %6.1f MiB\n",
                            row.mesh.c_str(), row.resolution, (unsigned long long)row.hyvox_voxels,
                            (unsigned long long)row.openvdb_voxels, row.stage_ms, row.call_ms, row.with_vdb_ms,
                            row.openvdb_ms, row.openvdb_ms / row.call_ms, row.openvdb_ms / row.with_vdb_ms,
                            row.hyvox_peak_mib, row.openvdb_peak_mib);
                std::fflush(stdout);
            }
        }

        table.write(out_dir);
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bench_mesh_to_volume: error: %s\n", e.what());
        return 1;
    }
}
