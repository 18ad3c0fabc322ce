// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// OpenVDB grids from voxelization results, for code that links OpenVDB itself (the tests
// and the benchmark; writeVdb serializes its grids without OpenVDB, vdb_direct_writer.h).
// The public API (hyvox/vdb.h) keeps OpenVDB types out.
#include <openvdb/openvdb.h>

#include <cstdint>
#include <string>
#include <vector>

#include "hyvox/grid.h"
#include "hyvox/result.h"
#include "hyvox/sparse_grid.h"
#include "vdb/vdb_direct_writer.h"  // densityGridBytes, checkGridBudget

namespace hyvox::vdb {

// openvdb::initialize(), once per process.
void initializeOpenVdb();

// Uniform scale voxel_size, translation origin + voxel_size/2: index (i,j,k) is the centre
// of voxel (i,j,k).
openvdb::math::Transform::Ptr makeTransform(const GridSpec& grid);

// "density": 1 on occupied voxels (active), background 0, fog volume. Built a whole 8³ leaf
// at a time, in parallel: each sparse leaf's words are the leaf's value mask, copied as they are.
// The tile bricks in `full_leaves` (sorted) become full leaves instead (the attribute grids'
// valued tile bricks: all grids get one tree shape).
openvdb::FloatGrid::Ptr makeDensityGrid(const GridSpec& grid, const SparseGrid& occupancy,
                                        const std::vector<std::uint64_t>& full_leaves = {});
// "count": the values of a multi-valued result.
openvdb::FloatGrid::Ptr makeCountGrid(const GridSpec& grid, const std::vector<VoxelCount>& counts);

// "sdf": result.sdf as an OpenVDB level set (class level set, background its band): leaves
// with the active voxels' distances and the inactive ones' ±background, the inside beyond the
// band as inactive tiles of -background.
openvdb::FloatGrid::Ptr makeLevelSetGrid(const VoxelizeResult& result);

// The grids writeVdb() stores (it serializes them itself, vdb_direct_writer.h): density,
// plus count when the method keeps counts (writesCountGrid), plus the attribute grids and the
// sdf, each with the hyvox_* metadata.
openvdb::GridPtrVec makeGrids(const VoxelizeResult& result);

// Writes grids with OpenVDB's own writer, atomically (hyvox::os::AtomicFile); throws
// InvalidInput / ResourceError; nothing is left behind on failure.
void writeGridsAtomic(const openvdb::GridCPtrVec& grids, const std::string& path);

}  // namespace hyvox::vdb
