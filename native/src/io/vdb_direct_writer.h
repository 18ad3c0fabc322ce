// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The .vdb file of a binary result, serialized straight from the sparse 8³ leaves without
// building an OpenVDB tree: OpenVDB reads it back as exactly the grid makeDensityGrid()
// builds (same tree, values, transform and metadata; test_io_vdb compares them).
//
// Why: building the tree allocates 2 KiB of floats per leaf, and OpenVDB's writer then
// walks, copies and compresses them one leaf at a time; here each leaf's bytes are a mask
// copy and a run of 1.0f, laid out in parallel in one buffer.
//
// Format: OpenVDB file version 224 (library 10.0), one grid "density" of type
// Tree_float_5_4_3, fog volume, background 0, compression COMPRESS_ACTIVE_MASK alone:
// every leaf stores its mask and only its active values (all 1.0). No blosc or zip on top:
// the file is about twice the size of OpenVDB's default (blosc), written in a fraction of
// the time, and every OpenVDB reader (Blender's included) reads it.
#include <cstddef>
#include <cstdint>
#include <memory>

#include "hyvox/result.h"

namespace hyvox::io {

struct VdbBytes {
    std::unique_ptr<char[]> data;
    std::size_t size = 0;
};

// The whole file (the caller writes it atomically). `threads`: 0 = all cores.
VdbBytes serializeDensityVdb(const VoxelizeResult& result, int threads);

// OpenVDB's Grid::memUsage() of that grid (its "file_mem_bytes" metadata).
std::uint64_t densityTreeMemUsage(const SparseGrid& occupancy);

}  // namespace hyvox::io
