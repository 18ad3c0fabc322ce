// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The part of one triangle inside one voxel's closed box, as a method that clips on the GPU
// (triangle, fragment, hybrid) hands it to the dispatcher, which turns a tile's pieces into
// attribute values with the cpu method's code (attributes::computePieceAttributes).
#include <array>
#include <cstdint>

namespace hyvox {

struct VoxelPiece {
    std::array<std::int32_t, 3> voxel;  // in the tile (voxel tile.offset of the grid is 0, 0, 0)
    std::uint32_t triangle;             // index into the tile job's mesh.usable
    float area;                         // voxel units²
    std::array<float, 3> centroid;      // relative to the voxel's min corner
    // Clipped only to the box grown by attributes::kTouchMargin (the exact clip lost a touch
    // to rounding): counts only for voxels no exact piece reached, as in the cpu method.
    bool margin;
};

}  // namespace hyvox
