// SPDX-License-Identifier: GPL-3.0-or-later
#include "gl/active_uniforms.h"

namespace hyvox::gl {

ActiveProgram::ActiveProgram(const Program& program) : program_(&program) {
    GLint count = 0;
    glGetProgramInterfaceiv(program.id(), GL_UNIFORM, GL_ACTIVE_RESOURCES, &count);
    const GLenum property = GL_LOCATION;
    for (GLint i = 0; i < count; ++i) {
        GLint location = -1;
        glGetProgramResourceiv(program.id(), GL_UNIFORM, GLuint(i), 1, &property, 1, nullptr, &location);
        if (location >= 0 && location < 64) active_ |= std::uint64_t(1) << location;
    }
}

}  // namespace hyvox::gl
