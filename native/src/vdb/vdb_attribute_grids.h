// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The attribute grids of a result (hyvox/attribute_grid.h) as OpenVDB grids, on the density
// grid's transform and active exactly on its voxels: "color" (Vec3f, linear RGB), "alpha"
// (float, when the colour source has it), "normal" (Vec3f, unit or zero).
#include <openvdb/openvdb.h>

#include "hyvox/result.h"

namespace hyvox::vdb {

openvdb::GridPtrVec makeAttributeGrids(const VoxelizeResult& result);

}  // namespace hyvox::vdb
