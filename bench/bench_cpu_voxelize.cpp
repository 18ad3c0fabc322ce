// SPDX-License-Identifier: GPL-3.0-or-later
// bench_cpu_voxelize MESH... [--res N]... [--mode conservative|thin] [--method cpu|reference]
//                   [--repeat R] [--threads T] [--out DIR]
// Prints, per mesh and resolution, the median (and minimum) of the backend's "voxelize" stage
// (what the goals measure), of the whole voxelize() call, and of the process CPU time spent in
// that call (all threads), plus the voxel count; the table also goes to DIR/cpu_voxelize.{json,md}
// (default bench/results/).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <string>
#include <vector>

#include "bench_args.h"
#include "bench_results.h"
#include "hyvox/mesh_io.h"
#include "hyvox/voxelize.h"

namespace {

// CPU time of the whole process: on a shared machine it shows the work done even when
// other processes take turns on the cores (wall time then overstates it).
double cpuMs() {
    timespec ts{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> meshes;
    std::vector<int> resolutions;
    hyvox::VoxelizeOptions options;
    int repeat = 7;
    std::string out_dir = HYVOX_BENCH_RESULTS_DIR;
    for (int a = 1; a < argc; ++a) {
        const std::string arg = argv[a];
        auto next = [&] { return hyvox::bench::optionValue(argc, argv, a); };
        if (arg == "--res")
            resolutions.push_back(std::atoi(next().c_str()));
        else if (arg == "--mode")
            options.mode = hyvox::parseMode(next());
        else if (arg == "--method")
            options.method = hyvox::parseMethod(next());
        else if (arg == "--repeat")
            repeat = std::max(1, std::atoi(next().c_str()));
        else if (arg == "--threads")
            options.threads = std::atoi(next().c_str());
        else if (arg == "--out")
            out_dir = next();
        else
            meshes.push_back(arg);
    }
    if (meshes.empty()) {
        std::fprintf(stderr,
                     "usage: bench_cpu_voxelize MESH... [--res N]... [--mode M] [--method M] [--repeat R] "
                     "[--threads T] [--out DIR]\n");
        return 2;
    }
    if (resolutions.empty()) resolutions = {256, 512};

    std::printf("%-34s %5s %-12s %10s %10s %10s %10s %12s\n", "mesh", "res", "mode", "voxel_ms", "min_ms", "total_ms",
                "cpu_ms", "voxels");
    hyvox::bench::ResultTable table("cpu_voxelize", "The cpu method's voxelize stage",
                                    {{"mesh"},
                                     {"res"},
                                     {"mode"},
                                     {"method"},
                                     {"stage ms", 2},
                                     {"stage min ms", 2},
                                     {"call ms", 2},
                                     {"call CPU ms", 2},
                                     {"voxels"}},
                                    argc, argv);
    table.note("Medians of " + std::to_string(repeat) + " calls, threads " +
               (options.threads ? std::to_string(options.threads) : std::string("all")) +
               "; call CPU: the process's CPU time during the call, all threads.");
    for (const std::string& path : meshes) {
        const hyvox::Mesh mesh = hyvox::readMesh(path);
        const std::string name = std::filesystem::path(path).filename().string();
        for (int res : resolutions) {
            options.grid.resolution = res;
            std::vector<double> stage, total, cpu;
            std::uint64_t voxels = 0;
            for (int r = 0; r < repeat; ++r) {
                const double cpu_before = cpuMs();
                const hyvox::VoxelizeResult result = hyvox::voxelize(mesh.view(), options);
                cpu.push_back(cpuMs() - cpu_before);
                stage.push_back(result.stats.timingMs("voxelize"));
                total.push_back(result.stats.totalMs());
                voxels = result.stats.voxel_count;
            }
            std::printf("%-34s %5d %-12s %10.2f %10.2f %10.2f %10.2f %12llu\n", name.c_str(), res,
                        hyvox::toString(options.mode), hyvox::bench::median(stage),
                        *std::min_element(stage.begin(), stage.end()), hyvox::bench::median(total),
                        hyvox::bench::median(cpu), static_cast<unsigned long long>(voxels));
            std::fflush(stdout);
            table.add({name, res, hyvox::toString(options.mode), hyvox::toString(options.method),
                       hyvox::bench::median(stage), *std::min_element(stage.begin(), stage.end()),
                       hyvox::bench::median(total), hyvox::bench::median(cpu), voxels});
        }
    }
    table.write(out_dir);
    return 0;
}
