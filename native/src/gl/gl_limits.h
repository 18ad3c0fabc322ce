// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The current context's implementation limits (GL_MAX_*), read on the GL worker thread.
#include <epoxy/gl.h>

namespace hyvox::gl {

inline GLint64 glLimit(GLenum name) {
    GLint64 value = 0;
    glGetInteger64v(name, &value);
    return value;
}

}  // namespace hyvox::gl
