// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The stats of a voxelization as JSON, for scripts and the benchmark:
// {"hyvox_version", "method", "mode", "origin": [x,y,z], "voxel_size", "dims": [x,y,z],
//  a region's run: "region": {"index", "count", "axis": "x"|"y"|"z", "lo": [i,j,k], "hi": [i,j,k]},
//  "voxel_count", "triangles": {"input","used","degenerate"}, "timings_ms": {stage: ms},
//  "total_ms", "options": {schema name: value used}, and the backend's section
//  "cpu" | "reference" | "hybrid" | "tessellation": {figure: value}}.
#include <string>

#include "hyvox/result.h"

namespace hyvox {

std::string statsToJson(const VoxelizeResult& result);

// `text` as a JSON string literal, quotes included (also a YAML double-quoted scalar and a
// JavaScript string: the farm job templates write theirs with it).
std::string jsonQuoted(const std::string& text);

// Writes text to a file atomically (temporary file in the same folder + rename; `durable`:
// synced to disk as the durable_write option says).
// Throws InvalidInput (bad path) or ResourceError (I/O failure); never leaves a partial file.
void writeTextFileAtomic(const std::string& path, const std::string& text, bool durable = false);

// InvalidInput when no file could be written at `path` (by writeTextFileAtomic, writeVdb):
// an empty path or one naming a folder, a folder, a device, FIFO or socket, a symlink to
// nothing, a folder that does not exist. A symlink to a regular file is fine (the file is
// replaced, the link kept). The writers check this themselves; front doors call it before
// long work so that the work is not done for nothing.
void checkOutputPath(const std::string& path);

}  // namespace hyvox
