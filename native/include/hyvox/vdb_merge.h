// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file
/// Joining the .vdb files of a region job (hyvox/region.h) into one: `hyvox merge` and
/// hyvox.merge_vdb. Each grid (density, count, color, alpha, normal, whatever the parts hold)
/// is joined by name, leaf by leaf: every part's leaves and tiles are taken as they are (their
/// masks and values, never a dense copy) and written with hyvox's own .vdb writer, so the
/// result is the file the one-machine run writes, byte for byte but for the file's random UUID.
#include <cstdint>
#include <string>
#include <vector>

#include "hyvox/interrupter.h"

namespace hyvox {

/// How mergeVdbFiles() writes its file: the threads and durability of WriteOptions (the
/// schema's "threads" and "durable_write").
struct MergeOptions {
    int threads = 0;       ///< cores that compress the leaves; 0 = all
    bool durable = false;  ///< synced to disk before returning, as WriteOptions::durable
};

/// What mergeVdbFiles() joined.
struct MergeReport {
    std::uint64_t parts = 0;   ///< the files read
    std::uint64_t grids = 0;   ///< the grids of each, and of the output
    std::uint64_t voxels = 0;  ///< the density grid's active voxels (or the first grid's)
    std::uint64_t leaves = 0;  ///< the leaves of that grid
    int regions = 0;           ///< N for the parts of a job of N regions; 0 for other files
    double read_ms = 0;        ///< reading and checking the parts, milliseconds
    double write_ms = 0;       ///< building and writing the output, milliseconds
};

/// Reads the parts (hyvox .vdb files: every grid has hyvox's metadata), checks that they fit
/// together and writes their union to `output` atomically (nothing is written on failure).
/// @param parts the .vdb files: the N parts of a region job, or any hyvox files of one grid
///        whose leaves do not overlap
/// @param output the file to write; must not be one of the parts
/// @param options threads and durability of the write
/// @param interrupter may be null; sees the progress (reading 0-80, writing 80-100)
/// @return what was joined, and the time of both stages
/// @throws InvalidInput a part that cannot be read or is not a .vdb file hyvox reads, a bad
///         output path, or parts that do not fit together, naming the files and what differs:
///         parts of different grids (voxel size, origin, dims, transform), methods, modes or
///         hyvox versions; a grid missing from a part or of another type, class or background;
///         parts of a region job (they carry hyvox_region "K/N") that are missing or given
///         twice; parts that overlap (two hold the same leaf); grids that hold inactive values
///         other than their background (a level set's inside), which the writer does not write
/// @throws ResourceError an I/O failure
/// @throws Cancelled the interrupter asked to stop (nothing written)
MergeReport mergeVdbFiles(const std::vector<std::string>& parts, const std::string& output,
                          const MergeOptions& options = {}, Interrupter* interrupter = nullptr);

}  // namespace hyvox
