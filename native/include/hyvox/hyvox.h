// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Umbrella header of the public C++ API.
#include "hyvox/bit_grid.h"
#include "hyvox/errors.h"
#include "hyvox/grid.h"
#include "hyvox/interrupter.h"
#include "hyvox/mesh.h"
#include "hyvox/option_schema.h"
#include "hyvox/options.h"
#include "hyvox/result.h"
#include "hyvox/voxelize.h"
