// SPDX-License-Identifier: GPL-3.0-or-later
// An open mesh's inside sampled both ways (solid/winding_less_crossings.h): from the fast
// winding numbers' tree and from the sheets of the open edges, the same surface, the same
// grid, one after the other in one process; the rule's pick (solid::bySheets) beside.
//
//   bench_open_sampling [--runs R] [--res N]... [--mesh-dir DIR] [--out DIR] [MESH[:x4|:x16]...]
//
// Columns:
//   open edges    after welding, those whose uses do not cancel (a term each per sheet point)
//   rule          what the solid pass picks for the mesh (open edges x 64 <= triangles: sheets)
//   tree ms, sheets ms   the inside pass (solid::fillInside) with each, median of R, taken in turn
//   tree / sheets  the ratio; above 1: the sheets are faster
//   voxels differ  inside voxels one has and the other not (each within its accuracy of the
//                  winding number 0.5: the tree's expansions err by up to about 0.03)
// A mesh argument "NAME:xN" subdivides it (N = 4 or 16) first: more triangles, and twice the
// open edges per level. The table also goes to DIR/open_sampling.{json,md} (default bench/results/).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "bench_args.h"
#include "bench_results.h"
#include "core/stopwatch.h"
#include "hyvox/hyvox.h"
#include "hyvox/mesh_io.h"
#include "solid/edge_closure.h"
#include "solid/fill_inside.h"
#include "support/subdivide.h"

namespace {

using hyvox::bench::median;

constexpr const char* kUsage =
    "usage: bench_open_sampling [--runs R] [--res N]... [--mesh-dir DIR] [--out DIR] [MESH[:x4|:x16]...]\n"
    "  an open mesh's inside pass with its winding numbers sampled from the fast winding tree\n"
    "  and from the open edges' sheets\n"
    "  --runs R       timed runs of each per case, the median printed (default 3)\n"
    "  --res N        a resolution (repeatable; default 128, 256 and 512)\n"
    "  --mesh-dir DIR where mesh names without a '/' are read (default $HYVOX_MESH_DIR or the\n"
    "                 project's meshes)\n"
    "  --out DIR      write the table to DIR/open_sampling.json and .md (default bench/results/)\n"
    "  MESH           default: the bunny, the shark, the elephant, the bunny x16 and Sponza\n";

// The voxels one grid holds and the other not, brick by brick over the bricks either holds.
std::uint64_t differing(const hyvox::SparseGrid& a, const hyvox::SparseGrid& b) {
    std::vector<std::uint64_t> bricks;
    for (const hyvox::SparseGrid* grid : {&a, &b}) {
        for (const hyvox::SparseGrid::Leaf& leaf : grid->leaves()) bricks.push_back(leaf.brick);
        for (const hyvox::SparseGrid::TileRun& run : grid->tileRuns())
            for (std::uint64_t brick = run.begin; brick < run.end; ++brick) bricks.push_back(brick);
    }
    std::sort(bricks.begin(), bricks.end());
    bricks.erase(std::unique(bricks.begin(), bricks.end()), bricks.end());
    std::uint64_t count = 0;
    for (const std::uint64_t brick : bricks) {
        std::uint64_t x[hyvox::BitGrid::kWordsPerBrick], y[hyvox::BitGrid::kWordsPerBrick];
        a.brickWords(brick, x);
        b.brickWords(brick, y);
        for (int w = 0; w < hyvox::BitGrid::kWordsPerBrick; ++w)
            count += std::uint64_t(__builtin_popcountll(x[w] ^ y[w]));
    }
    return count;
}

}  // namespace

int main(int argc, char** argv) try {
    std::string out_dir = HYVOX_BENCH_RESULTS_DIR;
    hyvox::bench::MeshBenchArgs args =
        hyvox::bench::parseMeshBenchArgs(argc, argv, kUsage, HYVOX_BENCH_MESH_DIR, out_dir);
    if (args.resolutions.empty()) args.resolutions = {128, 256, 512};
    if (args.files.empty())
        args.files = {"bunny_stanford_69k.ply", "shark_holes.ply", "elephant_holes.ply", "bunny_stanford_69k.ply:x16",
                      "sponza_crytek_262k_vcolor.ply.gz"};
    const int runs = args.runs;
    hyvox::bench::ResultTable table("open_sampling",
                                    "An open mesh's winding numbers from the fast winding tree and from the open "
                                    "edges' sheets",
                                    {{"mesh"},
                                     {"triangles"},
                                     {"open edges"},
                                     {"res"},
                                     {"rule"},
                                     {"tree ms", 1},
                                     {"sheets ms", 1},
                                     {"tree / sheets", 2},
                                     {"inside voxels"},
                                     {"voxels differ"}},
                                    argc, argv);
    table.note("The solid pass's inside step (solid::fillInside) on the same surface and grid, each way " +
               std::to_string(runs) +
               " times in turn, medians. The rule samples a mesh from its sheets when its open edges x 64 <= its "
               "triangles.");
    std::printf("%-36s %9s %6s %5s %7s %9s %10s %6s %12s %8s\n", "mesh", "triangles", "open", "res", "rule", "tree ms",
                "sheets ms", "ratio", "inside", "differ");
    for (const std::string& spec : args.files) {
        std::string file = spec;
        int levels = 0;
        if (const auto colon = spec.rfind(":x"); colon != std::string::npos) {
            file = spec.substr(0, colon);
            levels = spec.substr(colon + 2) == "16" ? 2 : 1;
        }
        const std::string path = file.find('/') == std::string::npos ? args.mesh_dir + "/" + file : file;
        hyvox::Mesh mesh = hyvox::readMesh(path);
        if (levels > 0) mesh = hyvox::test::midpointSubdivide(mesh.view(), levels);
        const std::string label =
            std::filesystem::path(path).filename().string() + (levels ? spec.substr(spec.rfind(':')) : "");
        const hyvox::ValidatedMesh validated = hyvox::validate(mesh.view());
        for (const int resolution : args.resolutions) {
            hyvox::VoxelizeOptions options;
            options.grid.resolution = resolution;
            const hyvox::VoxelizeResult surface = hyvox::voxelize(mesh.view(), options);
            options.mode = hyvox::Mode::Solid;
            const hyvox::solid::EdgeClosure closure = hyvox::solid::checkEdges(validated, surface.grid);
            if (closure.open_edges.empty()) {
                std::printf("%-36s closed: by ray crossings, no sampling\n", label.c_str());
                break;
            }
            std::vector<double> times[2];
            hyvox::SparseGrid inside[2];
            const hyvox::solid::OpenSampling ways[2] = {hyvox::solid::OpenSampling::Tree,
                                                        hyvox::solid::OpenSampling::Sheets};
            for (int r = 0; r < runs; ++r)
                for (int w = 0; w < 2; ++w) {
                    hyvox::SolidStats stats;
                    hyvox::Stopwatch watch;
                    inside[w] = hyvox::solid::fillInside(validated, surface.grid, surface.occupancy, options, closure,
                                                         nullptr, stats, nullptr, ways[w]);
                    times[w].push_back(watch.elapsedMs());
                }
            const bool sheets = hyvox::solid::bySheets(closure.open_edges.size(), validated.usable.size());
            const double tree_ms = median(times[0]), sheets_ms = median(times[1]);
            const std::uint64_t differ = differing(inside[0], inside[1]);
            std::printf("%-36s %9zu %6zu %5d %7s %9.1f %10.1f %6.2f %12llu %8llu\n", label.c_str(),
                        validated.usable.size(), closure.open_edges.size(), resolution, sheets ? "sheets" : "tree",
                        tree_ms, sheets_ms, tree_ms / sheets_ms, (unsigned long long)inside[1].count(),
                        (unsigned long long)differ);
            std::fflush(stdout);
            table.add({label, validated.usable.size(), closure.open_edges.size(), resolution,
                       sheets ? "sheets" : "tree", tree_ms, sheets_ms, tree_ms / sheets_ms, inside[1].count(), differ});
        }
    }
    table.write(out_dir);
    return 0;
} catch (const std::exception& e) {
    std::fprintf(stderr, "bench_open_sampling: %s\n", e.what());
    return 1;
}
