// SPDX-License-Identifier: GPL-3.0-or-later
// The GL entry points voxelize() links to, for the fuzz build that has no GL: the fuzzer
// runs only the cpu and reference methods, so reaching one of these is itself a finding.
#include <cstdlib>

#include "core/backends.h"
#include "gl/device_limits.h"

namespace hyvox {
void runHybridBackend(const BackendJob&, TileOutput&, Stats&) { std::abort(); }
void runTessellationBackend(const BackendJob&, TileOutput&, Stats&) { std::abort(); }
namespace gl {
std::uint64_t maxStorageBlockBytes(const std::string&) { std::abort(); }
}  // namespace gl
}  // namespace hyvox
