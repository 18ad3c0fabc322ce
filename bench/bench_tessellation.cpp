// SPDX-License-Identifier: GPL-3.0-or-later
// Times the tessellation method against the exact methods (cpu, and hybrid when this build
// and machine have it) per mesh and resolution, with its bias against the cpu result (the
// conservative voxels missed) and against the thin, 6-separating cpu result, and whether it
// is sealed: no 6-connected flood from outside reaches what the thin cpu voxels enclose
// (hyvox::floodFromOutside). One row per γ, so `--gammas 1,2` puts the old default beside
// the new one. Dense stand-ins for the paper's Asian Dragon: the 871k dragon
// midpoint-subdivided 4× and 16×.
//   bench_tessellation [--res 128,256,512,1024] [--gammas 1,2] [--repeat 3] [--csv FILE] [--out DIR] MESH...
// A mesh argument "NAME.ply.gz:xN" subdivides it (N = 4 or 16) on the CPU first.
// Times are the voxelize stage (wall ms, best of --repeat runs after one warm-up); the
// tessellation's GPU passes (timer queries, or wall time on llvmpipe) are listed apart.
// The table also goes to DIR/tessellation.{json,md} (default bench/results/).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#include "bench_args.h"
#include "bench_results.h"
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

template <typename T>
std::vector<T> parseList(const std::string& text) {
    std::vector<T> out;
    for (const std::string& item : hyvox::bench::splitList(text)) out.push_back(T(std::atof(item.c_str())));
    return out;
}

// "yes", "no (N)" with N voxels leaked, or "-" when the thin voxels enclose nothing (an
// open mesh), where the flood test says nothing.
std::string sealedText(const hyvox::SealReport& seal) {
    if (seal.enclosed == 0) return "-";
    return seal.sealed() ? "yes" : "no (" + std::to_string(seal.leaked) + ")";
}

struct Timed {
    hyvox::VoxelizeResult result;
    double best_ms = 0;
    std::string error;
};

Timed timeMethod(const hyvox::Mesh& mesh, const hyvox::VoxelizeOptions& options, int repeat) {
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
    std::vector<double> gammas{hyvox::TessellationOptions().gamma};
    int repeat = 3;
    std::string csv_path;
    std::string out_dir = HYVOX_BENCH_RESULTS_DIR;
    std::vector<std::string> meshes;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        auto next = [&] { return hyvox::bench::optionValue(argc, argv, i); };
        if (arg == "--res")
            resolutions = parseList<int>(next());
        else if (arg == "--gammas")
            gammas = parseList<double>(next());
        else if (arg == "--repeat")
            repeat = std::max(1, std::atoi(next().c_str()));
        else if (arg == "--csv")
            csv_path = next();
        else if (arg == "--out")
            out_dir = next();
        else
            meshes.push_back(arg);
    }
    if (meshes.empty()) {
        std::fprintf(stderr,
                     "usage: %s [--res 128,256] [--gammas 1,2] [--repeat 3] [--csv FILE] [--out DIR] "
                     "MESH[:x4|:x16]...\n",
                     argv[0]);
        return 2;
    }
    std::FILE* csv = csv_path.empty() ? nullptr : std::fopen(csv_path.c_str(), "w");
    if (csv)
        std::fprintf(csv,
                     "mesh,triangles,resolution,method,gamma,ms,gpu_pass_ms,points,voxels,bias,bias_thin,"
                     "false_voxels,enclosed,leaked\n");
    std::printf(
        "| mesh | triangles | res | cpu ms | hybrid ms | γ | tessellation ms (GPU passes) | points | bias | "
        "bias vs thin | false | sealed |\n");
    std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n");
    hyvox::bench::ResultTable table("tessellation", "The tessellation method: time, bias and watertightness per γ",
                                    {{"mesh"},
                                     {"triangles"},
                                     {"res"},
                                     {"cpu ms", 1},
                                     {"hybrid ms", 1},
                                     {"γ"},
                                     {"tessellation ms", 1},
                                     {"GPU passes ms", 1},
                                     {"points"},
                                     {"bias %", 2},
                                     {"bias vs thin %", 2},
                                     {"false voxels"},
                                     {"sealed"}},
                                    argc, argv);
    table.setGpu(hyvox::bench::glDevicesText());
    table.note("Times: the voxelize stage, best of " + std::to_string(repeat) +
               " runs after a warm-up. bias: the exact conservative voxels the points miss; bias vs thin: the "
               "exact 6-separating voxels they miss; false: voxels outside the conservative set; sealed: no "
               "6-connected flood from outside reaches what the thin voxels enclose (\"-\": they enclose "
               "nothing), \"no (N)\" with N voxels reached.");
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
                // The exact references, once per mesh and resolution.
                hyvox::VoxelizeOptions thin_options = options;
                thin_options.method = hyvox::Method::Cpu;
                thin_options.mode = hyvox::Mode::Thin;
                const hyvox::VoxelizeResult thin = hyvox::voxelize(mesh.view(), thin_options);
                char hybrid_ms[64];
                if (hybrid.error.empty())
                    std::snprintf(hybrid_ms, sizeof hybrid_ms, "%.1f", hybrid.best_ms);
                else
                    std::snprintf(hybrid_ms, sizeof hybrid_ms, "n/a");
                if (csv) {
                    std::fprintf(csv, "%s,%zu,%d,cpu,,%.3f,,,%llu,,,,,\n", name.c_str(), mesh.triangleCount(), res,
                                 cpu.best_ms, (unsigned long long)cpu.result.stats.voxel_count);
                    if (hybrid.error.empty())
                        std::fprintf(csv, "%s,%zu,%d,hybrid,,%.3f,,,%llu,,,,,\n", name.c_str(), mesh.triangleCount(),
                                     res, hybrid.best_ms, (unsigned long long)hybrid.result.stats.voxel_count);
                }
                for (double gamma : gammas) {
                    options.method = hyvox::Method::Tessellation;
                    options.tessellation.gamma = gamma;
                    options.tessellation.counts = false;  // binary voxelization, as the paper times it
                    const Timed tess = timeMethod(mesh, options, repeat);
                    if (!tess.error.empty()) {
                        std::printf("| %s | %zu | %d | γ %g: tessellation failed: %s |\n", name.c_str(),
                                    mesh.triangleCount(), res, gamma, tess.error.c_str());
                        continue;
                    }
                    const hyvox::TessellationStats& m = tess.result.stats.tessellation.value();
                    const double gpu_ms = m.pass0_gpu_ms + m.pass1_gpu_ms + m.pass2_gpu_ms;
                    hyvox::AccuracyReport acc;
                    if (cpu.error.empty()) acc = compareToReference(tess.result.occupancy, cpu.result.occupancy);
                    const hyvox::AccuracyReport acc_thin = compareToReference(tess.result.occupancy, thin.occupancy);
                    const hyvox::SealReport seal = floodFromOutside(tess.result.occupancy, thin.occupancy);
                    std::printf(
                        "| %s | %zu | %d | %.1f | %s | %g | %.1f (%.1f) | %.0f | %.2f%% | %.2f%% | %llu | %s "
                        "|\n",
                        name.c_str(), mesh.triangleCount(), res, cpu.best_ms, hybrid_ms, gamma, tess.best_ms, gpu_ms,
                        double(m.points), 100.0 * acc.bias, 100.0 * acc_thin.bias, (unsigned long long)acc.false_voxels,
                        sealedText(seal).c_str());
                    std::fflush(stdout);
                    char gamma_text[32];
                    std::snprintf(gamma_text, sizeof gamma_text, "%g", gamma);
                    table.add({name, mesh.triangleCount(), res, cpu.best_ms,
                               hybrid.error.empty() ? hyvox::bench::Cell(hybrid.best_ms) : hyvox::bench::Cell(),
                               std::string(gamma_text), tess.best_ms, gpu_ms, std::int64_t(m.points), 100.0 * acc.bias,
                               100.0 * acc_thin.bias, acc.false_voxels, sealedText(seal)});
                    if (csv) {
                        std::fprintf(csv, "%s,%zu,%d,tessellation,%g,%.3f,%.3f,%.0f,%llu,%.6f,%.6f,%llu,%llu,%llu\n",
                                     name.c_str(), mesh.triangleCount(), res, gamma, tess.best_ms, gpu_ms,
                                     double(m.points), (unsigned long long)tess.result.stats.voxel_count, acc.bias,
                                     acc_thin.bias, (unsigned long long)acc.false_voxels,
                                     (unsigned long long)seal.enclosed, (unsigned long long)seal.leaked);
                        std::fflush(csv);
                    }
                }
            }
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        if (csv) std::fclose(csv);
        return 1;
    }
    if (csv) std::fclose(csv);
    table.write(out_dir);
    return 0;
}
