// SPDX-License-Identifier: GPL-3.0-or-later
// Times the tessellation method against the exact methods (cpu, and hybrid when this build
// and machine have it) per mesh and resolution, with its bias against the cpu result (the
// conservative voxels missed) and against the thin, 6-separating cpu result. Dense
// stand-ins for the paper's Asian Dragon: the 871k dragon midpoint-subdivided 4× and 16×.
//   bench_tessellation [--res 128,256,512,1024] [--gamma 1] [--repeat 3] [--csv FILE] MESH...
// A mesh argument "NAME.ply.gz:xN" subdivides it (N = 4 or 16) on the CPU first.
// Times are the voxelize stage (wall ms, best of --repeat runs after one warm-up); the
// tessellation's GPU passes (timer queries, or wall time on llvmpipe) are listed apart.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <sstream>
#include <string>
#include <vector>

#include "bench_args.h"
#include "hyvox/accuracy.h"
#include "hyvox/mesh_io.h"
#include "hyvox/voxelize.h"
#include "support/subdivide.h"

namespace {

// The method's own stages: everything but input validation, grid allocation and counting,
// which every method shares, so the columns compare the voxelizers themselves.
double methodStagesMs(const hyvox::VoxelizeResult& r) {
    double ms = 0;
    for (const auto& [stage, t] : r.stats.timings_ms)
        if (stage != "validate" && stage != "allocate" && stage != "count") ms += t;
    return ms;
}

std::vector<int> parseList(const std::string& text) {
    std::vector<int> out;
    std::stringstream in(text);
    std::string item;
    while (std::getline(in, item, ',')) out.push_back(std::atoi(item.c_str()));
    return out;
}

struct Timed {
    hyvox::VoxelizeResult result;
    double best_ms = 0;
    std::string error;
};

Timed timeMethod(const hyvox::Mesh& mesh, hyvox::VoxelizeOptions options, int repeat) {
    Timed t;
    try {
        t.result = hyvox::voxelize(mesh.view(), options);  // warm-up: context, shaders, caches
        t.best_ms = methodStagesMs(t.result);
        for (int i = 1; i < repeat; ++i) {
            hyvox::VoxelizeResult r = hyvox::voxelize(mesh.view(), options);
            if (methodStagesMs(r) < t.best_ms) {
                t.best_ms = methodStagesMs(r);
                t.result = std::move(r);
            }
        }
    } catch (const std::exception& e) {
        t.error = e.what();
    }
    return t;
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<int> resolutions{128, 256, 512, 1024};
    double gamma = 1.0;
    int repeat = 3;
    std::string csv_path;
    std::vector<std::string> meshes;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        auto next = [&] { return hyvox::bench::optionValue(argc, argv, i); };
        if (arg == "--res") resolutions = parseList(next());
        else if (arg == "--gamma") gamma = std::atof(next().c_str());
        else if (arg == "--repeat") repeat = std::max(1, std::atoi(next().c_str()));
        else if (arg == "--csv") csv_path = next();
        else meshes.push_back(arg);
    }
    if (meshes.empty()) {
        std::fprintf(stderr, "usage: %s [--res 128,256] [--gamma 1] [--repeat 3] [--csv FILE] MESH[:x4|:x16]...\n", argv[0]);
        return 2;
    }
    std::FILE* csv = csv_path.empty() ? nullptr : std::fopen(csv_path.c_str(), "w");
    if (csv) std::fprintf(csv, "mesh,triangles,resolution,method,ms,gpu_pass_ms,points,voxels,bias,bias_thin,false_voxels\n");
    std::printf("| mesh | triangles | res | cpu ms | hybrid ms | tessellation ms (GPU passes) | points | bias | bias vs thin | false |\n");
    std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    try {
        for (const std::string& spec : meshes) {
            const auto colon = spec.rfind(":x");
            const std::string path = colon == std::string::npos ? spec : spec.substr(0, colon);
            const int factor = colon == std::string::npos ? 1 : std::atoi(spec.c_str() + colon + 2);
            hyvox::Mesh mesh = hyvox::readMesh(path);
            if (factor > 1) {
                int levels = 0;
                for (int f = factor; f > 1; f /= 4) ++levels;  // 4 → 1 level, 16 → 2
                mesh = hyvox::test::midpointSubdivide(mesh.view(), levels);
            }
            std::string name = path.substr(path.find_last_of('/') + 1);
            if (factor > 1) name += " x" + std::to_string(factor);
            for (int res : resolutions) {
                hyvox::VoxelizeOptions options;
                hyvox::bench::readEnvironment(options);
                options.grid.resolution = res;
                options.method = hyvox::Method::Cpu;
                const Timed cpu = timeMethod(mesh, options, repeat);
                options.method = hyvox::Method::Hybrid;
                const Timed hybrid = timeMethod(mesh, options, repeat);
                options.method = hyvox::Method::Tessellation;
                options.tessellation.gamma = gamma;
                options.tessellation.counts = false;  // binary voxelization, as the paper times it
                const Timed tess = timeMethod(mesh, options, repeat);
                if (!tess.error.empty()) {
                    std::printf("| %s | %zu | %d | tessellation failed: %s |\n", name.c_str(), mesh.triangleCount(), res,
                                tess.error.c_str());
                    continue;
                }
                const hyvox::TessellationStats& m = tess.result.stats.tessellation.value();
                const double gpu_ms = m.pass0_gpu_ms + m.pass1_gpu_ms + m.pass2_gpu_ms;
                hyvox::AccuracyReport acc, acc_thin;
                if (cpu.error.empty()) {
                    acc = compareToReference(tess.result.occupancy, cpu.result.occupancy);
                    hyvox::VoxelizeOptions thin = options;
                    thin.method = hyvox::Method::Cpu;
                    thin.mode = hyvox::Mode::Thin;
                    acc_thin = compareToReference(tess.result.occupancy, hyvox::voxelize(mesh.view(), thin).occupancy);
                }
                char hybrid_ms[64];
                if (hybrid.error.empty()) std::snprintf(hybrid_ms, sizeof hybrid_ms, "%.1f", hybrid.best_ms);
                else std::snprintf(hybrid_ms, sizeof hybrid_ms, "n/a");
                std::printf("| %s | %zu | %d | %.1f | %s | %.1f (%.1f) | %.0f | %.2f%% | %.2f%% | %llu |\n", name.c_str(),
                            mesh.triangleCount(), res, cpu.best_ms, hybrid_ms, tess.best_ms, gpu_ms, double(m.points),
                            100.0 * acc.bias, 100.0 * acc_thin.bias, (unsigned long long)acc.false_voxels);
                std::fflush(stdout);
                if (csv) {
                    std::fprintf(csv, "%s,%zu,%d,cpu,%.3f,,,%llu,,,\n", name.c_str(), mesh.triangleCount(), res,
                                 cpu.best_ms, (unsigned long long)cpu.result.stats.voxel_count);
                    if (hybrid.error.empty())
                        std::fprintf(csv, "%s,%zu,%d,hybrid,%.3f,,,%llu,,,\n", name.c_str(), mesh.triangleCount(), res,
                                     hybrid.best_ms, (unsigned long long)hybrid.result.stats.voxel_count);
                    std::fprintf(csv, "%s,%zu,%d,tessellation,%.3f,%.3f,%.0f,%llu,%.6f,%.6f,%llu\n", name.c_str(),
                                 mesh.triangleCount(), res, tess.best_ms, gpu_ms, double(m.points),
                                 (unsigned long long)tess.result.stats.voxel_count, acc.bias, acc_thin.bias,
                                 (unsigned long long)acc.false_voxels);
                    std::fflush(csv);
                }
            }
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        if (csv) std::fclose(csv);
        return 1;
    }
    if (csv) std::fclose(csv);
    return 0;
}
