// SPDX-License-Identifier: GPL-3.0-or-later
#include "gamma_sweep_command.h"

#include <chrono>
#include <cstdio>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "command_support.h"
#include "hyvox/accuracy.h"
#include "hyvox/hyvox.h"
#include "hyvox/mesh_io.h"
#include "hyvox/stats_json.h"
#include "hyvox/version.h"
#include "progress_line.h"

namespace hyvox::cli {
namespace {

struct SweepRow {
    double gamma = 0;
    AccuracyReport accuracy;       // against the exact conservative voxels
    AccuracyReport accuracy_thin;  // against the exact thin (6-separating) voxels
    SealReport seal;               // the flood test, against the thin voxels' inside
    double points = 0;
    std::uint64_t voxels = 0;
    double ms = 0;  // the whole voxelize() call, GL context already running
};

std::string sweepJson(const GridSpec& grid, std::uint64_t reference_voxels, std::uint64_t thin_reference_voxels,
                      const std::vector<SweepRow>& rows, const GammaBiasFit* fit) {
    std::ostringstream json;
    json.precision(17);
    json << "{\"hyvox_version\": \"" << version() << "\", \"dims\": [" << grid.dims[0] << ", " << grid.dims[1] << ", "
         << grid.dims[2] << "], \"voxel_size\": " << grid.voxel_size << ", \"reference_voxels\": " << reference_voxels
         << ", \"thin_reference_voxels\": " << thin_reference_voxels << ", \"rows\": [";
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const SweepRow& r = rows[i];
        json << (i ? ", " : "") << "{\"gamma\": " << r.gamma << ", \"bias\": " << r.accuracy.bias
             << ", \"missed_voxels\": " << r.accuracy.missed_voxels << ", \"bias_thin\": " << r.accuracy_thin.bias
             << ", \"missed_thin_voxels\": " << r.accuracy_thin.missed_voxels
             << ", \"enclosed_voxels\": " << r.seal.enclosed << ", \"leaked_voxels\": " << r.seal.leaked
             << ", \"sealed\": " << (r.seal.sealed() ? "true" : "false") << ", \"points\": " << r.points
             << ", \"voxels\": " << r.voxels << ", \"ms\": " << r.ms << "}";
    }
    json << "], \"fit\": ";
    if (fit)
        json << "{\"A\": " << fit->A << ", \"B\": " << fit->B << "}";
    else
        json << "null";
    json << "}\n";
    return json.str();
}

}  // namespace

void runGammaSweep(const Arguments& args, const std::atomic<bool>& stop) {
    const auto thread_limit = limitThreads(args.options.threads);
    checkOutputPaths(args.mesh_path, "", args.stats_json_path);
    ProgressLine interrupter = progressFor(args, stop);  // Ctrl-C stops the reading too
    const Mesh mesh = readMesh(args.mesh_path, &interrupter, meshReadOptions(args));

    VoxelizeOptions exact_options = args.options;
    exact_options.method = Method::Cpu;
    exact_options.mode = Mode::Conservative;
    const VoxelizeResult exact = voxelize(mesh.view(), exact_options, &interrupter);
    exact_options.mode = Mode::Thin;
    const VoxelizeResult thin = voxelize(mesh.view(), exact_options, &interrupter);
    const GridSpec& grid = exact.grid;
    if (!args.quiet) {
        std::printf(
            "hyvox %s gamma-sweep: %s, %zu triangles, %d x %d x %d voxels; exact references: conservative %llu "
            "voxels, thin %llu\n",
            version(), args.mesh_path.c_str(), mesh.triangleCount(), grid.dims[0], grid.dims[1], grid.dims[2],
            (unsigned long long)exact.stats.voxel_count, (unsigned long long)thin.stats.voxel_count);
        // "leaked": voxels the thin set encloses that a 6-connected flood from outside the
        // grid reaches through the result's empty voxels (0 = sealed; meaningful for closed
        // meshes, an open one encloses nothing).
        std::printf("%8s %10s %10s %10s %12s %12s %10s\n", "gamma", "bias", "bias_thin", "leaked", "points", "voxels",
                    "ms");
    }

    // One untimed run first, so the first row's time does not include starting the GL
    // context and compiling the shaders.
    voxelize(mesh.view(), args.options, &interrupter);

    std::vector<SweepRow> rows;
    std::vector<double> gammas, biases;
    for (double gamma : args.gammas) {
        VoxelizeOptions options = args.options;
        options.tessellation.gamma = gamma;
        const auto start = std::chrono::steady_clock::now();
        const VoxelizeResult r = voxelize(mesh.view(), options, &interrupter);
        const double ms = msSince(start);
        SweepRow row{gamma,
                     compareToReference(r.occupancy, exact.occupancy),
                     compareToReference(r.occupancy, thin.occupancy),
                     floodFromOutside(r.occupancy, thin.occupancy),
                     double(r.stats.tessellation->points),
                     r.stats.voxel_count,
                     ms};
        if (!args.quiet)
            std::printf("%8.3f %10.5f %10.5f %10llu %12.0f %12llu %10.1f\n", gamma, row.accuracy.bias,
                        row.accuracy_thin.bias, (unsigned long long)row.seal.leaked, row.points,
                        (unsigned long long)row.voxels, row.ms);
        std::fflush(stdout);
        rows.push_back(row);
        gammas.push_back(gamma);
        biases.push_back(row.accuracy.bias);
    }

    // No fit when the points already cover everything at all but one gamma: say so, and
    // still leave the table (and its JSON) behind.
    std::optional<GammaBiasFit> fit;
    try {
        fit = fitGammaBias(gammas, biases);
    } catch (const InvalidInput& e) {
        if (!args.quiet) std::printf("no Eq. 3 fit: %s\n", e.what());
    }
    if (fit && !args.quiet) {
        std::printf("Eq. 3 fit: gamma = -B ln(A bias) with A = %.5g, B = %.5g\n", fit->A, fit->B);
        for (double p : {0.05, 0.02, 0.01, 0.005}) std::printf("  bias %5.3f needs gamma %.3f\n", p, fit->gammaFor(p));
    }
    if (!args.stats_json_path.empty())
        writeTextFileAtomic(
            args.stats_json_path,
            sweepJson(grid, exact.stats.voxel_count, thin.stats.voxel_count, rows, fit ? &*fit : nullptr),
            args.write.durable);
}

}  // namespace hyvox::cli
