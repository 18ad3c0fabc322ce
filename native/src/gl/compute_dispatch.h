// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// One compute invocation per item (triangle), for shaders that number their items with
// shaders/common/compute_index.glsl: work groups along x, then y when one dimension's
// work-group count is not enough; `depth` work groups along z (chunks of one item).
#include <cstdint>

#include "gl/gl_objects.h"

namespace hyvox::gl {

void dispatchPerItem(const Program& program, std::uint64_t count, std::uint32_t depth = 1);

}  // namespace hyvox::gl
