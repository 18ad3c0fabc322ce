// SPDX-License-Identifier: GPL-3.0-or-later
// hyvox::writeVdb: the result's grids serialized directly (vdb_direct_writer.h) and written
// atomically. No OpenVDB header here on purpose: a program that writes through this file
// alone (the CLI) does not load libopenvdb at start-up (see the header of
// vdb_direct_writer.h); vdb_grid.cpp builds the same grids with OpenVDB for code that wants
// them as OpenVDB objects, and the tests check that both agree.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ostream>
#include <string>
#include <vector>

#include "hyvox/errors.h"
#include "hyvox/option_schema.h"
#include "hyvox/vdb.h"
#include "os/atomic_file.h"
#include "vdb/vdb_direct_writer.h"

namespace hyvox::vdb {

std::uint64_t densityGridBytes(const SparseGrid& occupancy) { return fogGridMemUsageForLeaves(occupancy.leafCount()); }

void checkGridBudget(const VoxelizeResult& result, const WriteOptions& options) {
    const AttributeGrid& a = result.attributes;
    const double leaves = double(result.occupancy.leafCount() + a.valued_tile_bricks.size());
    // The sdf's leaves hold a value for each of their 512 voxels, band or not.
    const double sdf_leaves = double(result.sdf.leaves.size());
    const double need = vdbWriterBytes(leaves, double(result.occupancy.tileCount()), double(a.valuedVoxelCount()),
                                       double(a.channels())) +
        (sdf_leaves > 0 ? vdbWriterBytes(sdf_leaves, 0, sdf_leaves * 512.0, 1.0) : 0.0);
    if (need > double(options.memoryBudgetBytes()))
        throw ResourceError("writing the .vdb of " + std::to_string(result.occupancy.leafCount()) +
                            " leaves needs about " + std::to_string(std::uint64_t(need / double(1 << 20)) + 1) +
                            " MiB, more than the memory budget of " + std::to_string(options.memoryBudgetMib()) +
                            " MiB; raise the budget (memory_budget_mib) or use a larger voxel size");
}

namespace {

// The "count" grid's leaves: the counts grouped by 8³ brick, each with its mask and values.
struct CountLeaves {
    struct Leaf {
        std::array<std::int32_t, 3> origin;
        std::uint64_t mask[8];
        float values[512];
    };
    std::vector<Leaf> storage;
    std::vector<VdbLeaf> leaves;
};

CountLeaves countLeaves(const std::vector<VoxelCount>& counts) {
    std::vector<const VoxelCount*> sorted(counts.size());
    for (std::size_t n = 0; n < counts.size(); ++n) sorted[n] = &counts[n];
    auto brickOf = [](const VoxelCount& c) { return std::array<std::int32_t, 3>{c.i >> 3, c.j >> 3, c.k >> 3}; };
    std::sort(sorted.begin(), sorted.end(),
              [&](const VoxelCount* a, const VoxelCount* b) { return brickOf(*a) < brickOf(*b); });
    CountLeaves out;
    for (std::size_t n = 0; n < sorted.size(); ++n) {
        const VoxelCount& c = *sorted[n];
        if (n == 0 || brickOf(c) != brickOf(*sorted[n - 1])) {
            out.storage.emplace_back();
            CountLeaves::Leaf& leaf = out.storage.back();
            leaf.origin = {c.i & ~7, c.j & ~7, c.k & ~7};
            std::fill(std::begin(leaf.mask), std::end(leaf.mask), 0);
            std::fill(std::begin(leaf.values), std::end(leaf.values), 0.0f);
        }
        CountLeaves::Leaf& leaf = out.storage.back();
        const int offset = (c.i & 7) << 6 | (c.j & 7) << 3 | (c.k & 7);
        leaf.mask[offset >> 6] |= std::uint64_t(1) << (offset & 63);
        leaf.values[offset] = float(c.count);  // a voxel listed twice keeps its last count, as an accessor would
    }
    for (const CountLeaves::Leaf& leaf : out.storage) out.leaves.push_back({leaf.origin, leaf.mask, leaf.values});
    return out;
}

}  // namespace

std::uint64_t writeVdbFile(const std::string& path, const VoxelizeResult& result, const std::vector<VdbGrid>& grids,
                           int threads, bool durable, Interrupter* interrupter, int progress_from, int progress_to) {
    std::uint64_t mem_usage = 0;
    os::AtomicFile(path, durable ? os::Durability::Durable : os::Durability::Atomic).writeWith([&](std::ostream& out) {
        mem_usage = writeVdbGrids(out, result, grids, threads, interrupter, progress_from, progress_to);
    });
    return mem_usage;
}

bool writesCountGrid(const VoxelizeResult& result) {
    const VoxelizeOptions& options = result.stats.options;
    return !result.counts.empty() || (options.method == Method::Tessellation && options.tessellation.counts);
}

}  // namespace hyvox::vdb

namespace hyvox {

void checkVdbVoxelSize(double voxel_size) {
    // ScaleMap's own test (openvdb/math/Maps.h): |det| < 3 × Tolerance<double> (1e-15).
    if (voxel_size * voxel_size * voxel_size >= 3e-15) return;
    char text[256];
    std::snprintf(text, sizeof text,
                  "voxel size %.6g is below the smallest a .vdb file can hold (about 1.45e-05 world units: "
                  "OpenVDB needs voxel_size^3 >= 3e-15); scale the mesh up (e.g. millimetres, not metres)",
                  voxel_size);
    throw InvalidInput(text);
}

VdbWriteReport writeVdb(const VoxelizeResult& result, const std::string& path, const WriteOptions& options,
                        Interrupter* interrupter) {
    checkOptions(options);
    checkVdbVoxelSize(result.grid.voxel_size);
    vdb::checkGridBudget(result, options);
    const InterrupterRun run(interrupter, "hyvox write");
    VdbWriteReport report;
    auto start = std::chrono::steady_clock::now();
    std::vector<vdb::VdbGrid> grids{vdb::resultDensityGrid(result)};
    vdb::CountLeaves counts;
    if (vdb::writesCountGrid(result)) {
        counts = vdb::countLeaves(result.counts);
        vdb::VdbGrid count;
        count.name = "count";
        count.layout = vdb::VdbLeafValues::Dense;
        count.leaves = counts.leaves;
        grids.push_back(std::move(count));
    }
    vdb::appendAttributeGrids(grids, result.occupancy, result.attributes);  // color, alpha, normal
    if (!result.sdf.empty()) grids.push_back(vdb::levelSetGrid(result));
    throwIfInterrupted(interrupter, 10);
    auto now = std::chrono::steady_clock::now();
    report.build_ms = std::chrono::duration<double, std::milli>(now - start).count();
    report.grid_bytes = vdb::writeVdbFile(path, result, grids, options.threads, options.durable, interrupter, 11, 98);
    report.write_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - now).count();
    if (interrupter) interrupter->wasInterrupted(100);  // progress only: the file is in place
    return report;
}

}  // namespace hyvox
