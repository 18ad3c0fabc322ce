// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Bounded gzip decompression for .gz mesh files: a gzip bomb is refused when its output
// passes a limit (not when memory runs out), and a stream cut short is an error, not a
// silently shorter mesh.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "hyvox/interrupter.h"

namespace hyvox::mesh_io {

// The largest output readMesh accepts from `compressed_bytes` of gzip: at most the read's
// memory budget (`budget_bytes`), and at most 100 times the input but never below 256 MiB:
// real meshes compress a few times, bombs a thousand times (docs/mesh-formats.md).
std::uint64_t gzipOutputLimit(std::uint64_t compressed_bytes, std::uint64_t budget_bytes);

// Decompresses gzip bytes already in memory (`path` is quoted in errors), as readGzipFile
// does with a file's bytes; the gzip fuzzer's entry.
std::vector<char> gunzip(const std::vector<char>& compressed, const std::string& path, std::uint64_t max_output,
                         Interrupter* interrupter = nullptr);

// Decompresses the whole file (several concatenated gzip members too). Throws InvalidInput
// naming the file when it is not gzip, is corrupt, ends before its last member does, or
// would decompress to more than max_output bytes. `interrupter` (may be null) is asked
// after every MiB of output (hyvox::Cancelled).
std::vector<char> readGzipFile(const std::string& path, std::uint64_t max_output, Interrupter* interrupter = nullptr);

// readGzipFile with max_output = gzipOutputLimit(the file's size, budget_bytes): readMesh's.
std::vector<char> readGzipMeshFile(const std::string& path, std::uint64_t budget_bytes, Interrupter* interrupter);

}  // namespace hyvox::mesh_io
