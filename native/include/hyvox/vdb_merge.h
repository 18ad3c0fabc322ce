// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Joining the .vdb files of a region job (hyvox/region.h) into one: `hyvox merge` and
// hyvox.merge_vdb. Each grid (density, count, color, alpha, normal, whatever the parts hold)
// is joined by name, leaf by leaf: every part's leaves and tiles are taken as they are (their
// masks and values, never a dense copy) and written with hyvox's own .vdb writer, so the
// result is the file the one-machine run writes, byte for byte but for the file's random UUID.
#include <cstdint>
#include <string>
#include <vector>

#include "hyvox/interrupter.h"

namespace hyvox {

struct MergeOptions {
    int threads = 0;            // cores that compress the leaves; 0 = all
    bool durable_write = false;  // as the durable_write option: synced to disk before returning
};

struct MergeReport {
    std::uint64_t parts = 0;
    std::uint64_t grids = 0;
    std::uint64_t voxels = 0;  // the density grid's active voxels (or the first grid's)
    std::uint64_t leaves = 0;  // of that grid
    int regions = 0;           // N for the parts of a job of N regions; 0 for other files
    double read_ms = 0, write_ms = 0;
};

// Reads the parts (hyvox .vdb files: every grid has hyvox's metadata), checks that they fit
// together and writes their union to `output` atomically (nothing is written on failure).
// Refused with InvalidInput, naming the files and what differs: parts of different grids
// (voxel size, origin, dims, transform), methods, modes or hyvox versions; a grid missing from
// a part or of another type, class or background; parts of a region job that are missing or
// given twice (the parts of a job carry hyvox_region "K/N"); parts that overlap (two hold the
// same leaf); grids that hold inactive values other than their background (a level set's
// inside), which the writer does not write. `output` must not be one of the parts.
// `interrupter` (may be null): progress (reading 0-80, writing 80-100) and hyvox::Cancelled.
MergeReport mergeVdbFiles(const std::vector<std::string>& parts, const std::string& output,
                          const MergeOptions& options = {}, Interrupter* interrupter = nullptr);

}  // namespace hyvox
