// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The accuracy measures compare voxel sets of one grid; anything else is the caller's error.
#include "hyvox/bit_grid.h"
#include "hyvox/errors.h"

namespace hyvox::accuracy {

inline void requireSameDims(const BitGrid& a, const BitGrid& b) {
    if (a.dims() != b.dims()) throw InvalidInput("accuracy: the result and the reference have different dims");
}

}  // namespace hyvox::accuracy
