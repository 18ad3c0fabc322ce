// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The stats of a voxelization as JSON, for scripts and the benchmark:
// {"hyvox_version", "method", "mode", "origin": [x,y,z], "voxel_size", "dims": [x,y,z],
//  "voxel_count", "triangles": {"input","used","degenerate"}, "timings_ms": {stage: ms},
//  "total_ms", "options": {schema name: value used}, and the backend's section
//  "cpu" | "reference" | "hybrid" | "tessellation": {figure: value}}.
#include <string>

#include "hyvox/result.h"

namespace hyvox {

std::string statsToJson(const VoxelizeResult& result);

// Writes text to a file atomically (temporary file in the same folder + rename).
// Throws InvalidInput (bad path) or ResourceError (I/O failure); never leaves a partial file.
void writeTextFileAtomic(const std::string& path, const std::string& text);

}  // namespace hyvox
