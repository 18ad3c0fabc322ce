// SPDX-License-Identifier: GPL-3.0-or-later
#include "gl/gl_tuning.h"

namespace hyvox::gl {

GlTuning GlTuning::forDevice(bool software, const GlOptions& options) {
    GlTuning tuning;
    tuning.wall_timing = software || options.wall_timing;
    // 90² columns of at most 4 loop iterations each stay well below 65535.
    tuning.chunk_side = software ? 90 : 0;
    tuning.tess_instanced = software || options.tess_instanced;
    return tuning;
}

}  // namespace hyvox::gl
