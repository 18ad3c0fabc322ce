// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The formats read through assimp (mesh_formats.h) are read in a process of its own, the
// helper program hyvox_assimp_reader (assimp_reader_process.cpp), found beside the plugins
// (core/plugin_library.h), and the mesh comes back through a pipe (mesh_wire.h). Whatever
// the bytes make assimp do (abort on an assertion, crash, loop, allocate without end), it
// ends that process, never this one: a crash, a read past the time limit or past the memory
// budget is an InvalidInput naming the file and what happened. The interrupter is asked
// every 20 ms while the process runs; a stop ends it (hyvox::Cancelled).
#include <cstddef>
#include <cstdint>
#include <string>

#include "hyvox/mesh_io.h"

namespace hyvox::mesh_io {

// What the reader process may take.
struct AssimpReadLimits {
    std::uint64_t memory_bytes;  // its data segments past those it starts with (RLIMIT_DATA), and the mesh sent back
    double seconds;              // wall-clock time until it is ended
};

// The limits readMesh gives a read of `file_bytes` with `options` (mesh_io.h).
AssimpReadLimits assimpReadLimits(const MeshReadOptions& options, std::uint64_t file_bytes);

// Reads the file at `path` as the format `extension` names (assimp may look at files beside
// it, as glTF's buffers).
Mesh readWithAssimp(const std::string& path, const std::string& extension, const AssimpReadLimits& limits,
                    Interrupter* interrupter = nullptr);

// Reads decompressed bytes (sent to the process on its standard input) as `extension`.
Mesh readWithAssimp(const char* data, std::size_t size, const std::string& extension, const std::string& path,
                    const AssimpReadLimits& limits, Interrupter* interrupter = nullptr);

}  // namespace hyvox::mesh_io
