// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file
/// Writing a voxelization to an OpenVDB file. OpenVDB types stay out of this header (its
/// headers compile slowly); src/vdb/vdb_grid.h has the grid builders for code that links
/// OpenVDB itself.
///
/// The file holds:
///  - "density": a FloatGrid, class fog volume, value 1 on every occupied voxel (active),
///    background 0. Transform: uniform scale voxel_size, translation origin + voxel_size/2,
///    so index (i,j,k) is the centre of voxel (i,j,k) (docs/design.md, "Coordinates").
///  - "count": a FloatGrid with the per-voxel values of a multi-valued result (when the
///    method keeps them: the tessellation with tess_counts), same transform.
///  - "color" (Vec3f, linear RGB), "alpha" (float, when the colour source has it), "normal"
///    (Vec3f): the attribute voxels (result.attributes), active exactly on the density's voxels.
///  - "sdf": a FloatGrid of class level set (result.sdf, hyvox/level_set.h): the band's signed
///    distances (world units, negative inside) active, ±background elsewhere, background the
///    band's half-width; same transform.
///  Grid metadata: hyvox_version, hyvox_method, hyvox_mode, hyvox_voxel_size, hyvox_origin,
///  hyvox_dims, and for a region's run (the region option) hyvox_region "K/N".
#include <cstdint>
#include <string>

#include "hyvox/interrupter.h"
#include "hyvox/options.h"
#include "hyvox/result.h"

namespace hyvox {

/// What writeVdb() did.
struct VdbWriteReport {
    std::uint64_t grid_bytes = 0;  ///< the OpenVDB grids' own memory (Grid::memUsage), bytes
    double build_ms = 0;           ///< listing the grids' leaves and tiles, milliseconds
    double write_ms = 0;           ///< compressing and writing the grids and renaming the file, milliseconds
};

/// Refuses a voxel size no .vdb file can hold. OpenVDB refuses a transform whose scale
/// determinant (voxel_size³) is below 3e-15, so a .vdb cannot hold voxels smaller than about
/// 1.44e-5 world units. writeVdb() calls it; front doors that always write a .vdb call it
/// before the voxelization so the work is not done for nothing.
/// @param voxel_size the edge of one voxel, world units
/// @throws InvalidInput naming the size and the remedy
void checkVdbVoxelSize(double voxel_size);

/// Writes `result` as an OpenVDB file (the grids of this header's description).
///
/// Atomic: a temporary file in the same folder, renamed over `path` only after everything was
/// written. On any failure the temporary file is removed and an existing file at `path` is
/// left as it was. Synced to disk (file and folder) only when options.durable says so
/// (src/os/atomic_file.h: why not by default). The file is serialized leaf by leaf on up to
/// options.threads cores (src/vdb/vdb_direct_writer.h).
///
/// Thread safety: `result` is only read; several writes of one result may run at once (to
/// different paths).
/// @param result a voxelization (hyvox::voxelize), or one assembled by hand with a finished
///        occupancy
/// @param path the file to write; an existing file is replaced (its permissions kept), a
///        symlink to a regular file is followed (checkOutputPath() says what is refused)
/// @param options threads, durability and the memory budget of the write
/// @param interrupter may be null; sees the progress (building the grids 0-90, writing
///        90-100) and can cancel until the file is being written
/// @return the grids' memory and the time of both stages
/// @throws InvalidInput a bad path, a voxel size a .vdb cannot hold, or options out of their
///         limits (the schema's message)
/// @throws ResourceError an I/O failure, or grids that with `result` would not fit the memory
///         budget (refused before they are built)
/// @throws Cancelled the interrupter asked to stop (nothing written)
VdbWriteReport writeVdb(const VoxelizeResult& result, const std::string& path, const WriteOptions& options = {},
                        Interrupter* interrupter = nullptr);

}  // namespace hyvox
