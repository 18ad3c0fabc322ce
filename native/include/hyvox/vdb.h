// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Writing a voxelization to an OpenVDB file. OpenVDB types stay out of this header (its
// headers compile slowly); src/io/vdb_grid.h has the grid builders for code that links
// OpenVDB itself.
//
// The file holds:
//  - "density": a FloatGrid, class fog volume, value 1 on every occupied voxel (active),
//    background 0. Transform: uniform scale voxel_size, translation origin + voxel_size/2,
//    so index (i,j,k) is the centre of voxel (i,j,k) (docs/design.md, "Coordinates").
//  - "count": a FloatGrid with the per-voxel values of a multi-valued result (only when
//    result.counts is non-empty), same transform.
//  - "color" (Vec3f, linear RGB), "alpha" (float, when the colour source has it), "normal"
//    (Vec3f): the attribute voxels (result.attributes), active exactly on the density's voxels.
//  Grid metadata: hyvox_version, hyvox_method, hyvox_mode, hyvox_voxel_size, hyvox_origin,
//  hyvox_dims.
#include <cstdint>
#include <string>

#include "hyvox/interrupter.h"
#include "hyvox/result.h"

namespace hyvox {

// Writes atomically: a temporary file in the same folder, renamed over `path` only after
// everything was written. On any failure the temporary file is removed, an existing file
// at `path` is left as it was, and InvalidInput (bad path) or ResourceError (I/O failure)
// is thrown. Synced to disk (file and folder) only when the result's options say
// durable_write (stats.options; src/io/atomic_file.h: why not by default). A grid that would not fit the run's memory budget (the result's options), with
// the result it is made from, is refused before it is built (ResourceError). The file is
// serialized leaf by leaf on up to `threads` cores (0 = all; src/io/vdb_direct_writer.h), like
// VoxelizeOptions. `interrupter` (may be null) sees the progress (building the grids 0-90,
// writing 90-100) and can cancel until the file is being written (hyvox::Cancelled, nothing
// written).
struct VdbWriteReport {
    std::uint64_t grid_bytes = 0;  // the OpenVDB grids' own memory (Grid::memUsage)
    double build_ms = 0, write_ms = 0;
};
// OpenVDB refuses a transform whose scale determinant (voxel_size³) is below 3e-15, so a
// .vdb cannot hold voxels smaller than about 1.44e-5 world units. InvalidInput naming the
// size and the remedy; writeVdb calls it, and front doors that always write a .vdb call it
// before the voxelization so the work is not done for nothing.
void checkVdbVoxelSize(double voxel_size);

VdbWriteReport writeVdb(const VoxelizeResult& result, const std::string& path, int threads = 0,
                        Interrupter* interrupter = nullptr);

}  // namespace hyvox
