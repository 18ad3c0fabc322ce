// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// FBX is read by assimp (in its process: assimp_reader.h), which reads a binary FBX whose
// records disagree with themselves (an array whose byte length is not its count's) as some
// other mesh, without a word. Before assimp sees the file, its container is checked here:
// the header, every node record's end offset (inside its parent, children ending exactly at
// it), every property's type and size, every array's byte length against its count (a
// zlib-compressed array inflated to exactly that), and the closing null record. ASCII FBX
// (rare: every current exporter writes binary) is refused by name. The check only reads; a
// compressed array is inflated through a small buffer, and one over `max_bytes` is refused.
#include <cstddef>
#include <cstdint>
#include <string>

namespace hyvox::mesh_io {

// Throws InvalidInput ("mesh file 'NAME': FBX ...") for anything but a consistent binary FBX.
void checkFbxContainer(const char* data, std::size_t size, const std::string& name, std::uint64_t max_bytes);

}  // namespace hyvox::mesh_io
