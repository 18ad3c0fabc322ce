// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file
/// The one entry point: validate the mesh, lay out the grid, run the chosen backend.
#include "hyvox/errors.h"
#include "hyvox/interrupter.h"
#include "hyvox/mesh.h"
#include "hyvox/options.h"
#include "hyvox/result.h"

namespace hyvox {

/// Voxelizes a triangle mesh: checks `options` against the schema (hyvox/option_schema.h),
/// validates the mesh, lays out the grid (makeGrid, world units; docs/design.md, "Coordinates") and
/// runs options.method's backend into a sparse result.
///
/// Thread safety: reentrant. Several voxelizations may run at once from different threads;
/// each uses up to options.threads CPU threads (its own TBB arena), and the GL methods run on
/// a GL worker thread of their own per device. The mesh is only read, and must not change
/// while the call runs.
/// @param mesh the triangles (world units) and their optional attributes; validated here
/// @param options what decides the voxels (see VoxelizeOptions); checked first
/// @param interrupter may be null; sees 0-100 progress and may cancel at any milestone
/// @return the grid, the voxels (and counts and attributes where asked for) and the stats
/// @throws InvalidInput a bad mesh or an option out of its limits (the schema's message)
/// @throws ResourceError the grid, its tiles or its attribute values would exceed the memory
///         budget (refused before allocating) or a GPU limit
/// @throws BackendError the method cannot run here (no GL 4.5 device, no GL plugin)
/// @throws Cancelled the interrupter asked to stop; nothing is returned
VoxelizeResult voxelize(const MeshView& mesh, const VoxelizeOptions& options, Interrupter* interrupter = nullptr);

/// voxelize() for a mesh validate() already checked (the CLI lays out the grid first, to
/// refuse a voxel size its output cannot hold before the work). Throws as voxelize() does.
/// @param validated the result of validate() on the mesh; its view must still be valid
/// @param options as for voxelize()
/// @param interrupter may be null
/// @param validate_ms reported as the "validate" stage of the stats, milliseconds
VoxelizeResult voxelize(const ValidatedMesh& validated, const VoxelizeOptions& options, Interrupter* interrupter,
                        double validate_ms);

/// validate() (hyvox/mesh.h) run on up to options.threads CPU threads, as voxelize() runs it.
/// @throws InvalidInput as validate() does
/// @throws Cancelled the interrupter (may be null) asked to stop
ValidatedMesh validate(const MeshView& mesh, const VoxelizeOptions& options, Interrupter* interrupter);

}  // namespace hyvox
