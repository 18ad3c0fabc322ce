// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The one entry point: validate the mesh, lay out the grid, run the chosen backend.
#include "hyvox/errors.h"
#include "hyvox/interrupter.h"
#include "hyvox/mesh.h"
#include "hyvox/options.h"
#include "hyvox/result.h"

namespace hyvox {

// Throws InvalidInput, ResourceError, BackendError or Cancelled; never aborts.
VoxelizeResult voxelize(const MeshView& mesh, const VoxelizeOptions& options,
                        Interrupter* interrupter = nullptr);

}  // namespace hyvox
