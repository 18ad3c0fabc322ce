// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file
/// The stats of a voxelization as JSON, for scripts and the benchmark, and the atomic text
/// writer the front doors write it with.
#include <string>

#include "hyvox/result.h"

namespace hyvox {

/// The stats of `result` as a JSON object:
/// {"hyvox_version", "method", "mode", "origin": [x,y,z], "voxel_size", "dims": [x,y,z],
///  a region's run: "region": {"index", "count", "axis": "x"|"y"|"z", "lo": [i,j,k], "hi": [i,j,k]},
///  "voxel_count", "triangles": {"input","used","degenerate"}, "timings_ms": {stage: ms},
///  "total_ms", "options": {schema name: value the voxelization used}, and the backend's
///  section "cpu" | "reference" | "hybrid" | "tessellation": {figure: value}} (plus "solid"
///  in solid mode). Origin and voxel size in world units; NaN and infinities are null.
std::string statsToJson(const VoxelizeResult& result);

/// Writes text to a file atomically (a temporary file in the same folder, then a rename).
/// @param path the file to write (checkOutputPath() says what is refused)
/// @param text written as it is
/// @param durable also synced to disk (file and folder), as WriteOptions::durable says
/// @throws InvalidInput a bad path
/// @throws ResourceError an I/O failure; never leaves a partial file
void writeTextFileAtomic(const std::string& path, const std::string& text, bool durable = false);

/// Refuses a path no file could be written at (by writeTextFileAtomic, writeVdb): an empty
/// path or one naming a folder, a folder, a device, FIFO or socket, a symlink to nothing, a
/// folder that does not exist. A symlink to a regular file is fine (the file is replaced, the
/// link kept). The writers check this themselves; front doors call it before long work so
/// that the work is not done for nothing.
/// @throws InvalidInput naming the path and what is wrong with it
void checkOutputPath(const std::string& path);

}  // namespace hyvox
