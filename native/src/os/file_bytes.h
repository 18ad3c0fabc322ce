// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Whole files into memory, for the mesh readers. Only regular files are read: a FIFO or a
// device would block or never end, and a folder is not a mesh.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace hyvox::os {

// The file's size. Throws InvalidInput ("mesh file 'PATH': ...") when the path is missing,
// unreadable, a folder or not a regular file, or empty.
std::uint64_t checkMeshFile(const std::string& path);

// The file's bytes; at most `max_bytes` are read (more is an InvalidInput).
std::vector<char> readFileBytes(const std::string& path, std::size_t max_bytes);

// The first up to n bytes (fewer for a shorter file).
std::vector<char> readFilePrefix(const std::string& path, std::size_t n);

}  // namespace hyvox::os
