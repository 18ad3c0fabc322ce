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

// The same for a mesh validate() already checked (the CLI lays out the grid first, to
// refuse a voxel size its output cannot hold before the work); `validate_ms` is reported as
// the validate stage. validate() below runs in an arena of options.threads.
VoxelizeResult voxelize(const ValidatedMesh& validated, const VoxelizeOptions& options, Interrupter* interrupter,
                        double validate_ms);
ValidatedMesh validate(const MeshView& mesh, const VoxelizeOptions& options, Interrupter* interrupter);

}  // namespace hyvox
