// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <atomic>

#include "cli_args.h"

namespace hyvox::cli {

// Reads the mesh, voxelizes, writes the .vdb (and stats JSON) and prints a summary.
// Stops with hyvox::Cancelled once `stop` becomes true (Ctrl-C). Throws on any failure;
// nothing is written unless everything before it succeeded.
void runVoxelize(const Arguments& args, const std::atomic<bool>& stop);

}  // namespace hyvox::cli
