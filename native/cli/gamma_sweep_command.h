// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <atomic>

#include "cli_args.h"

namespace hyvox::cli {

// The γ ↔ bias relation of Eq. 3 (point-tessellated voxelization, section 4.1) on one mesh:
// voxelizes it exactly once (cpu, conservative), then with the tessellation method at each
// γ; prints bias, points, voxels and time per γ and the least-squares fit of
// γ = -B · ln(A · bias), with the γ a few biases need. --stats-json writes the same as JSON.
void runGammaSweep(const Arguments& args, const std::atomic<bool>& stop);

}  // namespace hyvox::cli
