// SPDX-License-Identifier: GPL-3.0-or-later
// The sdf attribute: hyvox::voxelize(attributes sdf) against OpenVDB's tools::meshToLevelSet (what
// Blender's Mesh to SDF Grid node runs), same voxel size, placement and band (3 voxels), same
// process, all cores on both sides, one run.
//
//   bench_sdf [--runs R] [--res N]... [--mesh-dir DIR] [--out DIR] [MESH...]   (--help: usage)
//
// Defaults: Spot, the Buddha and the 871k dragon (closed or nearly: their inside by ray crossings
// or winding numbers), the bunny and Sponza (open), at 128, 256, 512 and 1024; median of 3 runs.
// Columns:
//   hyvox ms    the voxelize() call, conservative mode with the sdf (surface, inside test, band)
//   openvdb ms  meshToLevelSet (its input arrays prepared untimed)
//   x           openvdb / hyvox
//   active      each side's band voxels
//   |d| diff    where both hold a voxel and agree on its sign: the largest difference of the
//               distances, in voxels (hyvox's are exact: OpenVDB's band is approximate)
//   sign differs voxels both hold whose signs differ (hyvox's |d| above 0.05 voxel)
//   exact check of up to 200 of those, the exact winding number (every triangle's solid angle) at
//               the voxel: how many hyvox signs right / OpenVDB right / too close to 0.5 to say
// The table also goes to DIR/sdf.{json,md} (default bench/results/).
#include <openvdb/tools/MeshToVolume.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "bench_args.h"
#include "bench_results.h"
#include "core/stopwatch.h"
#include "hyvox/hyvox.h"
#include "hyvox/mesh_io.h"
#include "hyvox/version.h"
#include "openvdb_arrays.h"
#include "solid/fast_winding.h"
#include "vdb/vdb_grid.h"

namespace {

using hyvox::bench::median;

struct Row {
    std::string mesh;
    int resolution = 0;
    std::size_t triangles = 0;
    std::string inside;  // hyvox's inside rule and how it was evaluated
    double hyvox_ms = 0, openvdb_ms = 0;
    std::uint64_t hyvox_active = 0, openvdb_active = 0, common = 0, sign_differs = 0;
    double max_difference = 0;  // voxels
    int checked = 0, hyvox_right = 0, openvdb_right = 0, unclear = 0;
};

// hyvox's level-set value at a voxel: (active, value).
struct Lookup {
    const hyvox::VoxelizeResult& r;
    bool at(int i, int j, int k, float& value) const {
        if (!r.occupancy.inside(i, j, k)) return false;
        const std::uint64_t brick = r.grid.bricks().indexOfVoxel(i, j, k);
        const auto& leaves = r.sdf.leaves;
        const auto it =
            std::lower_bound(leaves.begin(), leaves.end(), brick,
                             [](const hyvox::LevelSetGrid::Leaf& l, std::uint64_t b) { return l.brick < b; });
        if (it == leaves.end() || it->brick != brick) return false;
        const int v = (i & 7) * 64 + (j & 7) * 8 + (k & 7);
        if (!((it->active[v >> 6] >> (v & 63)) & 1)) return false;
        std::size_t index = it->first;
        for (int w = 0; w < (v >> 6); ++w) index += std::size_t(__builtin_popcountll(it->active[w]));
        index += std::size_t(__builtin_popcountll(it->active[v >> 6] & ((std::uint64_t(1) << (v & 63)) - 1)));
        value = r.sdf.values[index];
        return true;
    }
};

Row runCase(const std::string& name, const hyvox::Mesh& mesh, int resolution, int runs) {
    Row row;
    row.mesh = name;
    row.resolution = resolution;
    row.triangles = mesh.triangleCount();
    hyvox::VoxelizeOptions options;
    options.grid.resolution = resolution;
    options.attributes.sdf = true;  // band: the default, 3 voxels
    std::vector<double> ours, theirs;
    hyvox::VoxelizeResult result;
    for (int r = 0; r < runs; ++r) {
        hyvox::Stopwatch watch;
        result = hyvox::voxelize(mesh.view(), options);
        ours.push_back(watch.elapsedMs());
    }
    row.inside = result.stats.solid->inside_rule + " by " + result.stats.solid->evaluation;
    row.hyvox_active = result.sdf.activeCount();

    // OpenVDB on the same voxels: index (i,j,k) is voxel (i,j,k)'s centre.
    const auto transform = hyvox::vdb::makeTransform(result.grid);
    const hyvox::bench::OpenVdbArrays arrays = hyvox::bench::openvdbArrays(mesh);
    openvdb::FloatGrid::Ptr level_set;
    for (int r = 0; r < runs; ++r) {
        hyvox::Stopwatch watch;
        level_set =
            openvdb::tools::meshToLevelSet<openvdb::FloatGrid>(*transform, arrays.points, arrays.triangles, 3.0f);
        theirs.push_back(watch.elapsedMs());
    }
    row.hyvox_ms = median(ours);
    row.openvdb_ms = median(theirs);
    row.openvdb_active = level_set->activeVoxelCount();

    // The voxels both hold.
    const double s = result.grid.voxel_size;
    const Lookup lookup{result};
    std::vector<openvdb::Coord> differing;
    for (auto it = level_set->cbeginValueOn(); it; ++it) {
        const openvdb::Coord c = it.getCoord();
        float ours_value;
        if (!lookup.at(c.x(), c.y(), c.z(), ours_value)) continue;
        ++row.common;
        if ((ours_value < 0) == (*it < 0)) {
            row.max_difference = std::max(row.max_difference, std::fabs(double(ours_value) - double(*it)) / s);
        } else if (std::fabs(ours_value) > 0.05 * s) {
            ++row.sign_differs;
            differing.push_back(c);
        }
    }
    // A sample of the differing voxels against the exact winding number.
    const hyvox::ValidatedMesh validated = hyvox::validate(mesh.view());
    std::vector<std::array<hyvox::solid::Vec3, 3>> corners;
    for (const std::uint32_t t : validated.usable)
        corners.push_back({result.grid.toVoxel(validated.vertex(t, 0)), result.grid.toVoxel(validated.vertex(t, 1)),
                           result.grid.toVoxel(validated.vertex(t, 2))});
    const std::size_t step = std::max<std::size_t>(1, differing.size() / 200);
    for (std::size_t n = 0; n < differing.size() && row.checked < 200; n += step) {
        const openvdb::Coord c = differing[n];
        const hyvox::solid::Vec3 q{c.x() + 0.5, c.y() + 0.5, c.z() + 0.5};
        double w = 0;
        for (const auto& t : corners) w += hyvox::solid::triangleWinding(t[0], t[1], t[2], q);
        float ours_value = 0;
        lookup.at(c.x(), c.y(), c.z(), ours_value);
        ++row.checked;
        if (std::fabs(w - 0.5) < 0.1)
            ++row.unclear;
        else
            ++((ours_value < 0) == (w >= 0.5) ? row.hyvox_right : row.openvdb_right);
    }
    return row;
}

constexpr const char* kUsage =
    "usage: bench_sdf [--runs R] [--res N]... [--mesh-dir DIR] [--out DIR] [MESH...]\n"
    "  hyvox's sdf attribute against OpenVDB meshToLevelSet (band 3 voxels)\n"
    "  --runs R       timed runs per case, the median printed (default 3)\n"
    "  --res N        a resolution (repeatable; default 128, 256, 512 and 1024)\n"
    "  --mesh-dir DIR where mesh names without a '/' are read (default $HYVOX_MESH_DIR or the\n"
    "                 project's meshes)\n"
    "  --out DIR      write the table to DIR/sdf.json and .md (default bench/results/)\n"
    "  MESH           default: Spot, the Buddha, the 871k dragon, the bunny and Sponza\n";

}  // namespace

int main(int argc, char** argv) try {
    std::string out_dir = HYVOX_BENCH_RESULTS_DIR;
    hyvox::bench::MeshBenchArgs args =
        hyvox::bench::parseMeshBenchArgs(argc, argv, kUsage, HYVOX_BENCH_MESH_DIR, out_dir);
    if (args.resolutions.empty()) args.resolutions = {128, 256, 512, 1024};
    if (args.files.empty())
        args.files = {"spot_vcolor.ply", "happy_buddha_100k.ply", "dragon_stanford_871k.ply.gz",
                      "bunny_stanford_69k.ply", "sponza_crytek_262k_vcolor.ply.gz"};
    const int runs = args.runs;
    hyvox::vdb::initializeOpenVdb();
    hyvox::bench::ResultTable table("sdf", "The signed distance grid against OpenVDB's meshToLevelSet",
                                    {{"mesh"},
                                     {"res"},
                                     {"hyvox inside"},
                                     {"hyvox ms", 1},
                                     {"openvdb ms", 1},
                                     {"openvdb / hyvox", 2},
                                     {"hyvox active"},
                                     {"openvdb active"},
                                     {"max |d| difference, voxels", 3},
                                     {"signs differ"},
                                     {"sample checked"},
                                     {"hyvox right"},
                                     {"openvdb right"},
                                     {"unclear"}},
                                    argc, argv);
    table.note("Medians of " + std::to_string(runs) + " runs, band 3 voxels, OpenVDB " +
               openvdb::getLibraryAbiVersionString() +
               ". |d| difference: where both hold a voxel and agree on its sign (hyvox's distances are exact, "
               "OpenVDB's band approximate). Of a sample of the voxels whose signs differ, the exact winding "
               "number says which side is right (unclear: too close to 0.5 to say).");
    std::printf("%-30s %5s %-30s %10s %10s %6s %10s %10s %9s %9s %s\n", "mesh", "res", "hyvox inside", "hyvox ms",
                "openvdb ms", "x", "hyvox act", "vdb act", "|d| diff", "signs", "hyvox/vdb/unclear");
    for (const std::string& file : args.files) {
        const std::string path = file.find('/') == std::string::npos ? args.mesh_dir + "/" + file : file;
        const hyvox::Mesh mesh = hyvox::readMesh(path);
        const std::string label = std::filesystem::path(path).filename().string();
        for (const int res : args.resolutions) {
            const Row r = runCase(label, mesh, res, runs);
            std::printf("%-30s %5d %-30s %10.1f %10.1f %6.2f %10llu %10llu %9.3f %9llu %d/%d/%d\n", r.mesh.c_str(),
                        r.resolution, r.inside.c_str(), r.hyvox_ms, r.openvdb_ms, r.openvdb_ms / r.hyvox_ms,
                        (unsigned long long)r.hyvox_active, (unsigned long long)r.openvdb_active, r.max_difference,
                        (unsigned long long)r.sign_differs, r.hyvox_right, r.openvdb_right, r.unclear);
            std::fflush(stdout);
            table.add({r.mesh, r.resolution, r.inside, r.hyvox_ms, r.openvdb_ms, r.openvdb_ms / r.hyvox_ms,
                       r.hyvox_active, r.openvdb_active, r.max_difference, r.sign_differs, r.checked, r.hyvox_right,
                       r.openvdb_right, r.unclear});
        }
    }
    table.write(out_dir);
    return 0;
} catch (const std::exception& error) {
    std::fprintf(stderr, "bench_sdf: %s\n", error.what());
    return 1;
}
