// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The contract between the dispatcher (src/voxelize/) and each backend. The dispatcher has
// checked the options, validated the mesh and laid out the grid; it then runs the backend once
// per tile, a brick-aligned box of the grid, with the triangles that may reach that box.
// A backend sets the bits of the tile's voxels in `out.bits` (voxel (0,0,0) of the bits is
// voxel tile.offset of the grid), may add counts (in grid coordinates), and adds its timings
// and its typed section of the stats (Stats::cpu, ::reference, ::hybrid, ::tessellation),
// summed over tiles. Voxel coordinates are computed in the whole grid's voxel space and only
// then shifted by the (integer) offset, so a tiled run sets exactly the voxels of an untiled
// one. Geometry outside the tile is clipped by the backend, never wrapped. Backends neither
// include nor call one another.
#include <array>
#include <cstdint>
#include <vector>

#include "core/attribute_evaluator.h"
#include "core/attribute_leaf.h"
#include "core/voxel_piece.h"
#include "hyvox/bit_grid.h"
#include "hyvox/interrupter.h"
#include "hyvox/mesh.h"
#include "hyvox/options.h"
#include "hyvox/result.h"

namespace hyvox {

// A brick-aligned box of the grid: voxels offset .. offset + dims - 1.
struct Tile {
    std::array<std::int32_t, 3> offset{0, 0, 0};  // multiples of 8
    std::array<std::int32_t, 3> dims{1, 1, 1};
    std::int32_t last(int axis) const { return offset[axis] + dims[axis] - 1; }
};

struct BackendJob {
    const ValidatedMesh& mesh;  // usable: the triangles that may reach the tile
    // The whole mesh (usable: every usable triangle), for per-vertex attributes that average
    // over a vertex's triangles (the tessellation's normals): the same in every tile.
    const ValidatedMesh& whole_mesh;
    const GridSpec& grid;  // the whole grid
    const Tile& tile;
    const VoxelizeOptions& options;
    Interrupter* interrupter;  // may be null; percent is the tile's own 0..100
    // The attributes asked for, for a method that computes them itself (tessellation);
    // null = none (the dispatcher computes the exact methods' afterwards).
    const AttributeEvaluator* attributes = nullptr;
    // The GL methods clip the triangle/voxel pairs they find into out.pieces.
    bool clip_pieces = false;
};

struct TileOutput {
    BitGrid bits;                                  // dims = tile.dims
    std::vector<VoxelCount> counts;                // multi-valued methods, grid coordinates
    std::vector<AttributeLeaf> attributes;         // with job.attributes: every set voxel's values
    std::uint64_t attribute_voxels_unreached = 0;  // set voxels given no value (0)
    std::vector<VoxelPiece> pieces;                // with job.clip_pieces: every pair's piece
};

void runCpuBackend(const BackendJob& job, TileOutput& out, Stats& stats);        // src/cpu/
void runReferenceBackend(const BackendJob& job, TileOutput& out, Stats& stats);  // src/reference/
void runHybridBackend(const BackendJob& job, TileOutput& out, Stats& stats);  // src/hybrid/: triangle|fragment|hybrid
void runTessellationBackend(const BackendJob& job, TileOutput& out, Stats& stats);  // src/tessellation/

}  // namespace hyvox
