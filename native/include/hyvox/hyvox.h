// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file
/// Umbrella header of the public C++ API: meshes, options and their schema, voxelize() and its
/// result. Reading mesh files (hyvox/mesh_io.h), textures (hyvox/texture.h), writing .vdb files
/// (hyvox/vdb.h) and stats (hyvox/stats_json.h), accuracy measures (hyvox/accuracy.h) and the GL
/// devices (hyvox/gl_devices.h) have headers of their own.
#include "hyvox/bit_grid.h"
#include "hyvox/errors.h"
#include "hyvox/grid.h"
#include "hyvox/interrupter.h"
#include "hyvox/mesh.h"
#include "hyvox/option_schema.h"
#include "hyvox/options.h"
#include "hyvox/result.h"
#include "hyvox/voxelize.h"
