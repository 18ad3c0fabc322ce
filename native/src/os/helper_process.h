// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The other side of child_process.h: what a helper program hyvox started (the assimp reader,
// mesh_io/assimp_reader_process.cpp) asks of the system about itself.
#include <cstdint>
#include <string>
#include <vector>

namespace hyvox::os {

// Makes this process end with the one that started it, also when that one is killed; false
// when that one (`parent_id`, as ChildProcess::thisProcessId gave it) is already gone.
bool endWithParent(const std::string& parent_id);

// Limits the memory this process may take to `memory_bytes` more than it holds now (so the
// limit bounds what comes after, also in a sanitizer build), and leaves no core file; an
// allocation the limit refuses ends the process with `exit_code`.
void limitThisProcess(std::uint64_t memory_bytes, int exit_code);

// All of the standard input, up to its end.
std::vector<char> readStandardInput();
// Writes all of `bytes` to the standard output; false when it cannot.
bool writeStandardOutput(const std::string& bytes);

}  // namespace hyvox::os
