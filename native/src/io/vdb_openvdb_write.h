// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// writeVdb() through OpenVDB: the grids built as OpenVDB objects (vdb_grid.h, with the
// attribute grids) and written atomically. For results the direct serializer
// (vdb_direct_writer.h) cannot write yet; no OpenVDB header here, so callers stay free of it.
#include <string>

#include "hyvox/interrupter.h"
#include "hyvox/result.h"
#include "hyvox/vdb.h"

namespace hyvox::io {

VdbWriteReport writeWithOpenVdb(const VoxelizeResult& result, const std::string& path, int threads,
                                Interrupter* interrupter);

}  // namespace hyvox::io
