// SPDX-License-Identifier: GPL-3.0-or-later
#include "gl/compute_dispatch.h"

#include <algorithm>

#include "gl/binding_points.h"

namespace hyvox::gl {

void dispatchPerItem(const Program& program, std::uint64_t count, std::uint32_t depth) {
    // The program's own work-group size (HYVOX_LOCAL_SIZE unless a shader folder says otherwise).
    GLint local[3] = {HYVOX_LOCAL_SIZE, 1, 1};
    glGetProgramiv(program.id(), GL_COMPUTE_WORK_GROUP_SIZE, local);
    const std::uint64_t size = std::uint64_t(std::max(1, local[0]));
    const std::uint64_t groups = (count + size - 1) / size;
    if (groups == 0) return;
    GLint max_x = 65535;
    glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, 0, &max_x);
    const std::uint64_t gx = std::min<std::uint64_t>(groups, std::uint64_t(max_x));
    glDispatchCompute(GLuint(gx), GLuint((groups + gx - 1) / gx), depth);
}

}  // namespace hyvox::gl
