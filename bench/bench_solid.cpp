// SPDX-License-Identifier: GPL-3.0-or-later
// Solid voxelization: hyvox mode=solid (inside rule auto) against OpenVDB's meshToVolume with
// an unlimited interior band followed by sdfToFogVolume (what Blender's Mesh to Volume does
// with Fill Volume), same voxel size and placement, same process, same threads, one run.
//
//   bench_solid [--runs R] [--res N]... [--mesh-dir DIR] [--fog-dir DIR] [--out DIR] [MESH...]   (--help: usage)
//
// The table also goes to DIR/solid.{json,md} (default bench/results/).
// --fog-dir: also writes OpenVDB's active fog voxels inside hyvox's grid to
// DIR/MESH_RES.fog.ijk (int32 i, j, k per voxel, tiles expanded), for bench_solid_three_way.py.
//
// Defaults: the Buddha, the 871k dragon and Sponza at 256, 512 and 1024, median of 3 runs.
// Columns (milliseconds, medians):
//   hyvox     the hyvox::voxelize() call (surface + inside)
//   +vdb      that plus building the OpenVDB density grid (interior as tiles)
//   openvdb   meshToVolume (exterior band 1 voxel, interior unlimited) + sdfToFogVolume
// and the voxel sets: hyvox's count, OpenVDB's active fog voxels, the fog voxels hyvox does
// not set (its centre has a negative distance in OpenVDB's view but hyvox finds it outside)
// and hyvox's voxels whose centre OpenVDB puts outside less those on hyvox's surface
// (centres hyvox finds inside and OpenVDB outside).
#include <openvdb/tools/LevelSetUtil.h>
#include <openvdb/tools/MeshToVolume.h>

#include <cfloat>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <string>
#include <vector>

#include "bench_args.h"
#include "bench_results.h"
#include "core/stopwatch.h"
#include "hyvox/hyvox.h"
#include "hyvox/mesh_io.h"
#include "openvdb_arrays.h"
#include "vdb/vdb_grid.h"

namespace {

using hyvox::bench::median;

struct Row {
    std::string mesh, rule;
    int resolution = 0;
    double hyvox_ms = 0, with_vdb_ms = 0, openvdb_ms = 0;
    std::uint64_t hyvox_voxels = 0, openvdb_voxels = 0, openvdb_only = 0, hyvox_only_inside = 0;
};

Row runCase(const std::string& name, const hyvox::Mesh& mesh, int resolution, int runs, const std::string& fog_dir) {
    Row row;
    row.mesh = name;
    row.resolution = resolution;
    hyvox::VoxelizeOptions options;
    options.grid.resolution = resolution;
    options.mode = hyvox::Mode::Solid;
    hyvox::VoxelizeOptions surface_options = options;
    surface_options.mode = hyvox::Mode::Conservative;
    std::vector<double> ours, ours_vdb, theirs;
    hyvox::VoxelizeResult result;
    for (int r = 0; r < runs; ++r) {
        hyvox::Stopwatch watch;
        result = hyvox::voxelize(mesh.view(), options);
        ours.push_back(watch.restart());
        auto grid = hyvox::vdb::makeDensityGrid(result.grid, result.occupancy);
        ours_vdb.push_back(ours.back() + watch.restart());
    }
    row.rule = result.stats.solid->inside_rule + " by " + result.stats.solid->evaluation;
    row.hyvox_voxels = result.occupancy.count();
    const hyvox::VoxelizeResult surface = hyvox::voxelize(mesh.view(), surface_options);

    // OpenVDB on the same grid: index (i,j,k) is voxel (i,j,k)'s centre.
    // The adapter form of meshToVolume takes index-space points (as Blender passes them).
    const auto transform = hyvox::vdb::makeTransform(result.grid);
    const hyvox::bench::OpenVdbArrays arrays = hyvox::bench::openvdbArrays(mesh, transform.get());
    const std::vector<openvdb::Vec3s>& points = arrays.points;
    const std::vector<openvdb::Vec3I>& triangles = arrays.triangles;
    openvdb::FloatGrid::Ptr fog;
    for (int r = 0; r < runs; ++r) {
        hyvox::Stopwatch watch;
        openvdb::tools::QuadAndTriangleDataAdapter<openvdb::Vec3s, openvdb::Vec3I> adapter(points, triangles);
        fog = openvdb::tools::meshToVolume<openvdb::FloatGrid>(adapter, *transform, 1.0f, FLT_MAX);
        openvdb::tools::sdfToFogVolume(*fog);
        theirs.push_back(watch.restart());
    }
    row.hyvox_ms = median(ours);
    row.with_vdb_ms = median(ours_vdb);
    row.openvdb_ms = median(theirs);
    row.openvdb_voxels = fog->activeVoxelCount();
    // Fog voxels hyvox lacks (tiles of the fog expanded voxel by voxel).
    std::vector<std::int32_t> fog_voxels;
    for (auto it = fog->cbeginValueOn(); it; ++it) {
        const openvdb::CoordBBox box = it.getBoundingBox();
        for (auto c = box.begin(); c; ++c) {
            const openvdb::Coord p = *c;
            const bool in_grid = result.occupancy.inside(p.x(), p.y(), p.z());
            if (!in_grid || !result.occupancy.test(p.x(), p.y(), p.z())) ++row.openvdb_only;
            if (in_grid && !fog_dir.empty()) fog_voxels.insert(fog_voxels.end(), {p.x(), p.y(), p.z()});
        }
    }
    if (!fog_dir.empty()) {
        const std::string path =
            fog_dir + "/" + name.substr(name.find_last_of('/') + 1) + "_" + std::to_string(resolution) + ".fog.ijk";
        std::ofstream out(path, std::ios::binary);
        out.write(reinterpret_cast<const char*>(fog_voxels.data()),
                  std::streamsize(fog_voxels.size() * sizeof(std::int32_t)));
        if (!out) {
            std::fprintf(stderr, "cannot write %s\n", path.c_str());
            std::exit(1);
        }
    }
    // hyvox's inside voxels (not on its surface) that the fog lacks, leaf by leaf and tile by tile.
    auto accessor = fog->getConstAccessor();
    const hyvox::BrickLayout& bricks = result.occupancy.bricks();
    auto check = [&](int i, int j, int k) {
        if (!surface.occupancy.test(i, j, k) && !accessor.isValueOn(openvdb::Coord(i, j, k))) ++row.hyvox_only_inside;
    };
    for (const hyvox::SparseGrid::Leaf& leaf : result.occupancy.leaves()) {
        const auto at = bricks.at(leaf.brick);
        for (int n = 0; n < 512; ++n)
            if ((leaf.words[n >> 6] >> (n & 63)) & 1)
                check(8 * at[0] + (n >> 6), 8 * at[1] + ((n >> 3) & 7), 8 * at[2] + (n & 7));
    }
    for (const hyvox::SparseGrid::TileRun& run : result.occupancy.tileRuns())
        for (std::uint64_t b = run.begin; b < run.end; ++b) {
            const auto at = bricks.at(b);
            for (int n = 0; n < 512; ++n) check(8 * at[0] + (n >> 6), 8 * at[1] + ((n >> 3) & 7), 8 * at[2] + (n & 7));
        }
    return row;
}

constexpr const char* kUsage =
    "usage: bench_solid [--runs R] [--res N]... [--mesh-dir DIR] [--fog-dir DIR] [--out DIR] [MESH...]\n"
    "  hyvox mode=solid (inside rule auto) against OpenVDB meshToVolume + sdfToFogVolume\n"
    "  --runs R       timed runs per case, the median printed (default 3)\n"
    "  --res N        a resolution (repeatable; default 256, 512 and 1024)\n"
    "  --mesh-dir DIR where mesh names without a '/' are read (default $HYVOX_MESH_DIR or the\n"
    "                 project's meshes)\n"
    "  --fog-dir DIR  also write OpenVDB's fog voxels to DIR/MESH_RES.fog.ijk\n"
    "  --out DIR      write the table to DIR/solid.json and .md (default bench/results/)\n"
    "  MESH           default: the Buddha, the 871k dragon and Sponza\n";

}  // namespace

int main(int argc, char** argv) try {
    std::string fog_dir;
    std::string out_dir = HYVOX_BENCH_RESULTS_DIR;
    hyvox::bench::MeshBenchArgs args =
        hyvox::bench::parseMeshBenchArgs(argc, argv, kUsage, HYVOX_BENCH_MESH_DIR, [&](const std::string& arg, int& a) {
            if (arg == "--fog-dir")
                fog_dir = hyvox::bench::optionValue(argc, argv, a);
            else if (arg == "--out")
                out_dir = hyvox::bench::optionValue(argc, argv, a);
            else
                return false;
            return true;
        });
    const int runs = args.runs;
    std::vector<int>& resolutions = args.resolutions;
    const std::string& mesh_dir = args.mesh_dir;
    std::vector<std::string>& files = args.files;
    if (resolutions.empty()) resolutions = {256, 512, 1024};
    if (files.empty())
        files = {"happy_buddha_100k.ply", "dragon_stanford_871k.ply.gz", "sponza_crytek_262k_vcolor.ply.gz"};
    hyvox::vdb::initializeOpenVdb();
    std::printf("%-34s %5s %-34s %9s %9s %9s %7s %12s %12s %10s %10s\n", "mesh", "res", "hyvox rule", "hyvox", "+vdb",
                "openvdb", "x +vdb", "hyvox vox", "openvdb vox", "vdb-only", "hyvox-only");
    hyvox::bench::ResultTable table("solid", "Solid: hyvox mode=solid against OpenVDB meshToVolume + sdfToFogVolume",
                                    {{"mesh"},
                                     {"res"},
                                     {"hyvox inside rule"},
                                     {"hyvox ms", 1},
                                     {"hyvox + vdb ms", 1},
                                     {"OpenVDB ms", 1},
                                     {"OpenVDB / hyvox + vdb", 1},
                                     {"hyvox voxels"},
                                     {"OpenVDB voxels"},
                                     {"OpenVDB only"},
                                     {"hyvox only"}},
                                    argc, argv);
    table.note("Medians of " + std::to_string(runs) +
               " runs, all cores, the same grid. OpenVDB only: fog voxels hyvox leaves out; hyvox only: hyvox's "
               "inside voxels off its surface that the fog lacks. OpenVDB's sign flood needs a closed surface: "
               "on an open mesh (Sponza) its interior is wrong, by the brute-force winding number.");
    for (const std::string& file : files) {
        const std::string path = file.find('/') == std::string::npos ? mesh_dir + "/" + file : file;
        const hyvox::Mesh mesh = hyvox::readMesh(path);
        for (const int res : resolutions) {
            const Row r = runCase(file, mesh, res, runs, fog_dir);
            std::printf("%-34s %5d %-34s %9.1f %9.1f %9.1f %7.1f %12llu %12llu %10llu %10llu\n", r.mesh.c_str(),
                        r.resolution, r.rule.c_str(), r.hyvox_ms, r.with_vdb_ms, r.openvdb_ms,
                        r.openvdb_ms / r.with_vdb_ms, (unsigned long long)r.hyvox_voxels,
                        (unsigned long long)r.openvdb_voxels, (unsigned long long)r.openvdb_only,
                        (unsigned long long)r.hyvox_only_inside);
            std::fflush(stdout);
            table.add({r.mesh, r.resolution, r.rule, r.hyvox_ms, r.with_vdb_ms, r.openvdb_ms,
                       r.openvdb_ms / r.with_vdb_ms, r.hyvox_voxels, r.openvdb_voxels, r.openvdb_only,
                       r.hyvox_only_inside});
        }
    }
    table.write(out_dir);
    return 0;
} catch (const std::exception& error) {  // a mesh that cannot be read, a grid too large, ...
    std::fprintf(stderr, "bench_solid: %s\n", error.what());
    return 1;
}
