// SPDX-License-Identifier: GPL-3.0-or-later
// hyvox::mergeVdbFiles: the parts read back (vdb_reader.h), checked against each other, and
// their leaves and tiles handed as they are to the writer the one-machine run uses
// (vdb_direct_writer.h), which folds the parts' tiles into larger ones where they fill a node
// together, as that run's own tiles are.
#include "hyvox/vdb_merge.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <set>
#include <utility>

#include "hyvox/errors.h"
#include "hyvox/region.h"
#include "hyvox/version.h"
#include "vdb/vdb_direct_writer.h"
#include "vdb/vdb_reader.h"

namespace hyvox {
namespace {

using vdb::VdbFile;
using vdb::VdbReadGrid;
using vdb::VdbTile;

std::int32_t tileSide(const VdbTile& tile) { return tile.level == 1 ? 8 : tile.level == 2 ? 128 : 4096; }

struct Part {
    std::string path;
    VdbFile file;
};

// What a part says of its run: the hyvox_* metadata of its first grid (every grid holds it).
struct PartRun {
    GridSpec grid;
    std::string version, method, mode;
    RegionOptions region;
};

// The metadata the writer writes again, from the merged grids or the parts' run: a part with
// any other entry is refused, so that nothing is dropped unnoticed.
const std::set<std::string>& carriedMetadata() {
    static const std::set<std::string> names{"class",
                                             "vector_type",
                                             "creator",
                                             "name",
                                             "file_bbox_min",
                                             "file_bbox_max",
                                             "file_compression",
                                             "file_mem_bytes",
                                             "file_voxel_count",
                                             "file_delayed_load",
                                             "hyvox_version",
                                             "hyvox_method",
                                             "hyvox_mode",
                                             "hyvox_voxel_size",
                                             "hyvox_origin",
                                             "hyvox_dims",
                                             "hyvox_region"};
    return names;
}

[[noreturn]] void refuse(const Part& part, const std::string& what) {
    throw InvalidInput("cannot merge '" + part.path + "': " + what);
}

template <typename T, std::size_t N>
std::array<T, N> metaArray(const Part& part, const VdbReadGrid& grid, const char* name, const char* type) {
    const vdb::VdbMetaEntry* entry = grid.meta(name);
    if (!entry)
        refuse(part,
               "grid '" + grid.name + "' has no " + name + " metadata: hyvox merge joins the .vdb files hyvox writes");
    if (entry->type != type || entry->bytes.size() != sizeof(T) * N)
        refuse(part, "grid '" + grid.name + "' has " + name + " metadata of type " + entry->type + ", not " + type);
    std::array<T, N> out;
    std::memcpy(out.data(), entry->bytes.data(), sizeof(T) * N);
    return out;
}

std::string metaString(const Part& part, const VdbReadGrid& grid, const char* name) {
    const vdb::VdbMetaEntry* entry = grid.meta(name);
    if (!entry || entry->type != "string")
        refuse(part,
               "grid '" + grid.name + "' has no " + name +
                   " text metadata: hyvox merge joins the .vdb files hyvox writes");
    return entry->bytes;
}

PartRun partRun(const Part& part) {
    if (part.file.grids.empty()) refuse(part, "it holds no grid");
    if (!part.file.metadata.empty())
        refuse(part,
               "it has file metadata ('" + part.file.metadata[0].name + "'), which hyvox merge does not carry over");
    for (const VdbReadGrid& grid : part.file.grids)
        for (const vdb::VdbMetaEntry& entry : grid.metadata)
            if (!carriedMetadata().count(entry.name))
                refuse(part,
                       "grid '" + grid.name + "' has metadata '" + entry.name +
                           "', which hyvox merge does not carry over");
    const VdbReadGrid& first = part.file.grids[0];
    PartRun run;
    run.grid.voxel_size = metaArray<double, 1>(part, first, "hyvox_voxel_size", "double")[0];
    run.grid.origin = metaArray<double, 3>(part, first, "hyvox_origin", "vec3d");
    run.grid.dims = metaArray<std::int32_t, 3>(part, first, "hyvox_dims", "vec3i");
    for (int a = 0; a < 3; ++a)
        if (run.grid.dims[a] < 1 || run.grid.dims[a] > kMaxResolution) refuse(part, "its hyvox_dims are out of range");
    run.version = metaString(part, first, "hyvox_version");
    run.method = metaString(part, first, "hyvox_method");
    run.mode = metaString(part, first, "hyvox_mode");
    if (first.meta("hyvox_region")) {
        const std::string text = metaString(part, first, "hyvox_region");
        if (!isRegionText(text) || parseRegion(text).whole())
            refuse(part, "its hyvox_region '" + text + "' is not K/N");
        run.region = parseRegion(text);
    }
    return run;
}

// The parts of a job: all of one N, each K once; or no part of a job at all.
// The job's N, 0 for files of no job.
int checkRegions(const std::vector<Part>& parts, const std::vector<PartRun>& runs) {
    const bool job = !runs[0].region.whole();
    for (std::size_t p = 1; p < parts.size(); ++p)
        if (runs[p].region.whole() != !job)
            refuse(
                parts[p],
                job ? "it is not a region of a job, and '" + parts[0].path + "' is"
                    : "it is region " + formatRegion(runs[p].region) + " of a job, and '" + parts[0].path + "' is not");
    if (!job) return 0;
    const int count = runs[0].region.count;
    std::vector<int> given(std::size_t(count), -1);
    for (std::size_t p = 0; p < parts.size(); ++p) {
        const RegionOptions& region = runs[p].region;
        if (region.count != count)
            refuse(parts[p],
                   "it is region " + formatRegion(region) + ", of a job of " + std::to_string(region.count) +
                       " regions; '" + parts[0].path + "' is of a job of " + std::to_string(count));
        int& seen = given[std::size_t(region.index)];
        if (seen >= 0)
            refuse(parts[p], "region " + formatRegion(region) + " is also '" + parts[std::size_t(seen)].path + "'");
        seen = int(p);
    }
    std::string missing;
    for (int k = 0; k < count; ++k)
        if (given[std::size_t(k)] < 0)
            missing += (missing.empty() ? "" : ", ") + std::to_string(k) + "/" + std::to_string(count);
    if (!missing.empty())
        throw InvalidInput("cannot merge a job of " + std::to_string(count) + " regions without region" +
                           (missing.find(',') == std::string::npos ? " " : "s ") + missing);
    return count;
}

void checkSameRun(const Part& part, const PartRun& run, const Part& first, const PartRun& expected) {
    auto differs = [&](const std::string& what, const std::string& here, const std::string& there) {
        refuse(part, "its " + what + " is " + here + ", and '" + first.path + "''s is " + there);
    };
    auto vec = [](const auto& v) {
        return "(" + std::to_string(v[0]) + ", " + std::to_string(v[1]) + ", " + std::to_string(v[2]) + ")";
    };
    if (run.grid.voxel_size != expected.grid.voxel_size)
        differs("voxel size", std::to_string(run.grid.voxel_size), std::to_string(expected.grid.voxel_size));
    if (run.grid.origin != expected.grid.origin)
        differs("grid origin", vec(run.grid.origin), vec(expected.grid.origin));
    if (run.grid.dims != expected.grid.dims) differs("grid", run.grid.dimsText(), expected.grid.dimsText());
    if (run.method != expected.method) differs("method", run.method, expected.method);
    if (run.mode != expected.mode) differs("mode", run.mode, expected.mode);
    if (run.version != expected.version) differs("hyvox version", run.version, expected.version);
}

std::string gridNames(const VdbFile& file) {
    std::string names;
    for (const VdbReadGrid& grid : file.grids) names += (names.empty() ? "" : ", ") + grid.name;
    return names;
}

// Grid g of `part` fits grid g of the first part: name, type, class, vector type, transform,
// and a background of 0 without other inactive values (what the writer writes).
void checkGrid(const Part& part, const VdbReadGrid& grid, const Part& first, const VdbReadGrid& expected,
               const std::string& transform) {
    if (grid.name != expected.name)
        refuse(part,
               "its grids are " + gridNames(part.file) + ", and '" + first.path + "''s are " + gridNames(first.file));
    const std::string what = "grid '" + grid.name + "'";
    if (grid.type != expected.type)
        refuse(part, what + " holds other values than in '" + first.path + "' (float, Vec3f)");
    if (grid.metaText("class") != expected.metaText("class"))
        refuse(part,
               what + " is of class '" + grid.metaText("class") + "', in '" + first.path + "' of class '" +
                   expected.metaText("class") + "'");
    if (grid.metaText("vector_type") != expected.metaText("vector_type"))
        refuse(part,
               what + " has vector type '" + grid.metaText("vector_type") + "', in '" + first.path + "' '" +
                   expected.metaText("vector_type") + "'");
    if (grid.transform != transform)
        refuse(part,
               what + "'s transform is not the uniform scale and translation of its hyvox_voxel_size and hyvox_origin");
    const bool zero_background = std::all_of(grid.background.begin(), grid.background.begin() + grid.channels(),
                                             [](float v) { return v == 0.0f; });
    if (!zero_background || !grid.inactive_tiles.empty() || !grid.inactive_values.empty())
        refuse(part,
               what +
                   " holds inactive values other than a background of 0 (a level set?), which hyvox merge "
                   "does not write");
}

// Leaf origins (and level-1 tiles) held by two parts.
void checkDisjoint(const std::vector<Part>& parts, std::size_t g) {
    struct Item {
        std::array<std::int32_t, 3> origin;
        std::size_t part;
        bool operator<(const Item& other) const { return origin < other.origin; }
    };
    std::vector<Item> items;
    for (std::size_t p = 0; p < parts.size(); ++p) {
        const VdbReadGrid& grid = parts[p].file.grids[g];
        for (const VdbReadGrid::Leaf& leaf : grid.leaves) items.push_back({leaf.origin, p});
        for (const VdbTile& tile : grid.tiles)
            if (tile.level == 1) items.push_back({tile.origin, p});
    }
    std::sort(items.begin(), items.end());
    for (std::size_t n = 1; n < items.size(); ++n)
        if (items[n].origin == items[n - 1].origin) {
            const auto& o = items[n].origin;
            const std::size_t a = std::min(items[n].part, items[n - 1].part),
                              b = std::max(items[n].part, items[n - 1].part);
            refuse(parts[b],
                   "it and '" + parts[a].path + "' both hold voxels of the leaf at (" + std::to_string(o[0]) + ", " +
                       std::to_string(o[1]) + ", " + std::to_string(o[2]) + ") of grid '" +
                       parts[a].file.grids[g].name + "' (the regions of one job never overlap)");
        }
}

// A region's part holds nothing outside its box.
void checkInsideBox(const Part& part, const PartRun& run) {
    const RegionBox box = regionBox(run.grid, run.region);
    const int a = box.axis;
    const std::int32_t end = (box.hi[a] + 7) / 8 * 8;  // the box's last leaf ends here
    for (const VdbReadGrid& grid : part.file.grids) {
        auto outside = [&](std::int32_t lo, std::int32_t side) { return lo < box.lo[a] || lo + side > end; };
        bool any = false;
        for (const VdbReadGrid::Leaf& leaf : grid.leaves) any = any || outside(leaf.origin[a], 8);
        for (const VdbTile& tile : grid.tiles) any = any || outside(tile.origin[a], tileSide(tile));
        if (any)
            refuse(part,
                   "grid '" + grid.name + "' holds voxels outside the box of its region " + formatRegion(run.region) +
                       " (voxels " + std::to_string(box.lo[a]) + " to " + std::to_string(box.hi[a] - 1) + " along " +
                       "xyz"[a] + ")");
    }
}

std::uint64_t tileVoxels(const VdbTile& tile) {
    const std::uint64_t side = std::uint64_t(tileSide(tile));
    return side * side * side;
}

// Grid g of every part as one grid for the writer. `storage` keeps the values of parts whose
// leaves all hold one value when the merged grid needs them voxel by voxel.
vdb::VdbGrid mergedGrid(const std::vector<Part>& parts, std::size_t g, std::vector<std::vector<float>>& storage) {
    const VdbReadGrid& first = parts[0].file.grids[g];
    vdb::VdbGrid out;
    out.name = first.name;
    out.type = first.type;
    out.grid_class = first.metaText("class");
    out.vector_type = first.metaText("vector_type");
    const std::size_t width = std::size_t(first.channels());
    // One value on every part's leaves: written as Fill (the density).
    bool uniform = true, seen = false;
    std::array<float, 3> fill{};
    for (const Part& part : parts) {
        const VdbReadGrid& grid = part.file.grids[g];
        if (grid.activeLeafVoxels() == 0) continue;
        if (!grid.uniform ||
            (seen && !std::equal(fill.begin(), fill.begin() + long(width), grid.uniform_value.begin())))
            uniform = false;
        fill = grid.uniform_value;
        seen = true;
    }
    out.layout = uniform ? vdb::VdbLeafValues::Fill : vdb::VdbLeafValues::Packed;
    out.fill = fill;
    out.stride = width;
    for (const Part& part : parts) {
        const VdbReadGrid& grid = part.file.grids[g];
        const float* values = grid.values.data();
        if (!uniform && grid.uniform) {
            storage.emplace_back();
            for (std::uint64_t v = 0; v < grid.activeLeafVoxels(); ++v)
                storage.back().insert(storage.back().end(), grid.uniform_value.begin(),
                                      grid.uniform_value.begin() + long(width));
            values = storage.back().data();
        }
        for (const VdbReadGrid::Leaf& leaf : grid.leaves)
            out.leaves.push_back({leaf.origin, leaf.mask, uniform ? nullptr : values + leaf.first * width});
        out.tiles.insert(out.tiles.end(), grid.tiles.begin(), grid.tiles.end());
    }
    return out;
}

double msSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

MergeReport mergeVdbFiles(const std::vector<std::string>& paths, const std::string& output, const MergeOptions& options,
                          Interrupter* interrupter) {
    if (paths.empty()) throw InvalidInput("merge: no .vdb file given");
    if (options.threads < 0) throw InvalidInput("merge: threads must be >= 0 (0 = all cores)");
    for (const std::string& path : paths) {
        std::error_code error;
        if (std::filesystem::equivalent(path, output, error) && !error)
            throw InvalidInput("merge: the output '" + output + "' is one of the parts ('" + path + "')");
    }
    const InterrupterRun run(interrupter, "hyvox merge");
    MergeReport report;
    auto start = std::chrono::steady_clock::now();
    std::vector<Part> parts;
    parts.reserve(paths.size());
    for (const std::string& path : paths) {
        throwIfInterrupted(interrupter, int(80 * parts.size() / paths.size()));
        parts.push_back({path, vdb::readVdbFile(path, interrupter)});
    }
    std::vector<PartRun> runs;
    for (const Part& part : parts) runs.push_back(partRun(part));
    for (std::size_t p = 1; p < parts.size(); ++p) checkSameRun(parts[p], runs[p], parts[0], runs[0]);
    report.regions = checkRegions(parts, runs);
    if (runs[0].version != version())
        refuse(parts[0],
               "it was written by hyvox " + runs[0].version + ", and this is hyvox " + version() +
                   ": merge the parts with the hyvox that voxelized them");
    const std::string transform = vdb::vdbTransformBytes(runs[0].grid);
    const VdbFile& first = parts[0].file;
    for (const Part& part : parts) {
        if (part.file.grids.size() != first.grids.size())
            refuse(part,
                   "its grids are " + gridNames(part.file) + ", and '" + parts[0].path + "''s are " + gridNames(first));
        for (std::size_t g = 0; g < first.grids.size(); ++g)
            checkGrid(part, part.file.grids[g], parts[0], first.grids[g], transform);
    }
    for (std::size_t p = 0; p < parts.size(); ++p)
        if (!runs[p].region.whole()) checkInsideBox(parts[p], runs[p]);
    for (std::size_t g = 0; g < first.grids.size(); ++g) checkDisjoint(parts, g);
    report.read_ms = msSince(start);

    start = std::chrono::steady_clock::now();
    throwIfInterrupted(interrupter, 80);
    // The writer takes the run's description from a result: the grid and the run's names.
    VoxelizeResult described;
    described.grid = runs[0].grid;
    described.stats.method = runs[0].method;
    described.stats.mode = runs[0].mode;
    std::vector<std::vector<float>> storage;
    std::vector<vdb::VdbGrid> grids;
    for (std::size_t g = 0; g < first.grids.size(); ++g) grids.push_back(mergedGrid(parts, g, storage));
    vdb::writeVdbFile(output, described, grids, options.threads, options.durable, interrupter, 81, 98);
    report.write_ms = msSince(start);

    std::size_t counted = 0;
    for (std::size_t g = 0; g < grids.size(); ++g)
        if (grids[g].name == "density") counted = g;
    for (const Part& part : parts) {
        const VdbReadGrid& grid = part.file.grids[counted];
        report.voxels += grid.activeLeafVoxels();
        for (const VdbTile& tile : grid.tiles) report.voxels += tileVoxels(tile);
        report.leaves += grid.leaves.size();
    }
    report.parts = parts.size();
    report.grids = grids.size();
    if (interrupter) interrupter->wasInterrupted(100);
    return report;
}

}  // namespace hyvox
