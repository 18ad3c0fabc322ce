// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file
/// The `sdf` attribute (option attributes, src/sdf/): a narrow-band signed distance field on
/// the run's grid, held as OpenVDB holds a level set (the .vdb's float grid "sdf", class
/// level set, on the density grid's transform):
///  - active voxels: those whose centre lies closer than the band's half-width w (option
///    sdf_band, in voxels) to the mesh. Each holds the distance from its centre to the nearest
///    triangle, computed exactly in double precision and stored as a float, in world units;
///    negative where the centre is inside by solid mode's inside rule (ray parity, or the
///    winding number: an open mesh keeps its inside where OpenVDB's flood fill leaks);
///  - every other voxel is inactive and holds -w·s inside and +w·s (the background) outside,
///    s the voxel size.
/// Only the grid's voxels are valued (the run pads the grid so that the band around the mesh
/// fits in it); outside the grid everything is outside.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "hyvox/bit_grid.h"
#include "hyvox/sparse_grid.h"

namespace hyvox {

/// The narrow-band level set of the `sdf` attribute (VoxelizeResult::sdf), as described above.
struct LevelSetGrid {
    float background = 0;  ///< w·s, world units; 0: no sdf was asked for
    /// One 8³ brick of the level set.
    struct Leaf {
        std::uint64_t brick;                            ///< BrickLayout index of the run's grid
        std::uint64_t active[BitGrid::kWordsPerBrick];  ///< the band's voxels (OpenVDB NodeMask<3> words)
        std::uint64_t inside[BitGrid::kWordsPerBrick];  ///< voxels whose centre is inside, active or not
        std::size_t first;                              ///< index in `values` of the first active voxel's
    };
    /// Bricks with band voxels, and bricks with inside and outside voxels but no band voxel
    /// (where an open mesh's inside ends away from its triangles); ascending.
    std::vector<Leaf> leaves;
    /// The active voxels' signed distances (world units), leaf by leaf, each leaf's in mask
    /// order (word by word, bit by bit).
    std::vector<float> values;
    /// Bricks wholly inside the grid and inside the mesh, without band voxels: inactive,
    /// -background. Runs of BrickLayout indices [begin, end), ascending.
    std::vector<SparseGrid::TileRun> inside_runs;

    bool empty() const { return background == 0; }               ///< no sdf was asked for
    std::uint64_t activeCount() const { return values.size(); }  ///< voxels within the band
    /// The bytes it holds.
    std::size_t byteSize() const {
        return leaves.capacity() * sizeof(Leaf) + values.capacity() * sizeof(float) +
            inside_runs.capacity() * sizeof(SparseGrid::TileRun);
    }
};

}  // namespace hyvox
