// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// .vdb files of fog-volume float grids serialized straight from 8³ leaf masks, without
// building an OpenVDB tree (and without OpenVDB): OpenVDB reads them back as exactly the
// grids makeGrids() (vdb_grid.h) builds — same trees, values, transforms and metadata
// (test_io_vdb_direct compares them).
//
// Why: building a tree allocates 2 KiB of floats per leaf, and OpenVDB's writer then walks,
// copies and compresses them one leaf at a time; here each leaf's bytes are a mask copy and
// its active values, laid out in parallel in one buffer. Programs that write only through
// this file (the CLI) also never load libopenvdb, whose start-up costs more than a small
// voxelization.
//
// Format: OpenVDB file version 224 (library 10.0), grids of type Tree_float_5_4_3, fog
// volume, background 0, compressed as OpenVDB 10 does by default (COMPRESS_BLOSC |
// COMPRESS_ACTIVE_MASK): every leaf stores its mask and only its active values, as one
// blosc block made with OpenVDB's settings (libblosc, which OpenVDB itself links), so the
// files are the size of OpenVDB's own and every OpenVDB reader (Blender's included) reads them.
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "hyvox/result.h"

namespace hyvox::io {

// One leaf: its first voxel (multiples of 8, >= 0), its 512-bit value mask (OpenVDB's
// NodeMask<3> words: word x, bit y * 8 + z), and its 512 values in the same order, or null
// for 1.0 on every active voxel. Inactive voxels hold the background, 0.
struct FogLeaf {
    std::array<std::int32_t, 3> origin;
    const std::uint64_t* mask;
    const float* values;
};

struct FogGrid {
    std::string name;
    std::vector<FogLeaf> leaves;  // any order; they must outlive serializeFogGrids()
};

struct VdbBytes {
    std::unique_ptr<char[]> data;
    std::size_t size = 0;
    std::uint64_t mem_usage = 0;  // the grids' Grid::memUsage() summed (see fogTreeMemUsage)
};

// The leaves of the "density" grid: the occupancy's own masks, 1.0 where set.
std::vector<FogLeaf> densityLeaves(const SparseGrid& occupancy);

// The whole file holding `grids` in order, each with the hyvox_* metadata of `result` and its
// grid transform. The caller writes it atomically. `threads`: 0 = all cores.
VdbBytes serializeFogGrids(const VoxelizeResult& result, const std::vector<FogGrid>& grids, int threads);

// OpenVDB's Grid::memUsage() of the grid these leaves make (its "file_mem_bytes" metadata).
std::uint64_t fogTreeMemUsage(const std::vector<FogLeaf>& leaves);

// An upper estimate of the memory OpenVDB would need for a float grid of `leaves` leaves.
std::uint64_t fogGridMemUsageForLeaves(std::uint64_t leaves);

// The memory the density grid of `occupancy` takes as an OpenVDB grid (float leaves of 512
// values): the measure of the memory budget, whichever writer runs.
std::uint64_t densityGridBytes(const SparseGrid& occupancy);
// ResourceError before anything is built when that grid and the result it is made from
// would not fit the run's memory budget (result.stats.options).
void checkGridBudget(const VoxelizeResult& result);

}  // namespace hyvox::io
