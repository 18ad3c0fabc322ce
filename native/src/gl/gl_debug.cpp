// SPDX-License-Identifier: GPL-3.0-or-later
#include "gl/gl_debug.h"

#include <epoxy/gl.h>

#include <string>

#include "hyvox/errors.h"

namespace hyvox::gl {
namespace {

// One GL context per thread (GlWorker), so a thread-local collector is the context's.
thread_local std::string pending_errors;

void GLAPIENTRY collect(GLenum source, GLenum type, GLuint, GLenum severity, GLsizei length, const GLchar* message,
                        const void*) {
    if (type != GL_DEBUG_TYPE_ERROR && severity != GL_DEBUG_SEVERITY_HIGH) return;
    // Compile failures are thrown by buildProgram with the file name and the full log.
    if (source == GL_DEBUG_SOURCE_SHADER_COMPILER) return;
    if (!pending_errors.empty()) pending_errors += "; ";
    pending_errors.append(message, length >= 0 ? std::size_t(length) : std::string(message).size());
}

}  // namespace

void enableDebugOutput() {
    if (epoxy_gl_version() < 43 && !epoxy_has_gl_extension("GL_KHR_debug")) return;
    glEnable(GL_DEBUG_OUTPUT);
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDebugMessageCallback(collect, nullptr);
    // Only what collect keeps: errors of any severity and anything of high severity, not
    // compiler messages. Each enabled message is a synchronous callback.
    glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DONT_CARE, 0, nullptr, GL_FALSE);
    glDebugMessageControl(GL_DONT_CARE, GL_DEBUG_TYPE_ERROR, GL_DONT_CARE, 0, nullptr, GL_TRUE);
    glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DEBUG_SEVERITY_HIGH, 0, nullptr, GL_TRUE);
    glDebugMessageControl(GL_DEBUG_SOURCE_SHADER_COMPILER, GL_DONT_CARE, GL_DONT_CARE, 0, nullptr, GL_FALSE);
}

void checkGl(const char* what) {
    std::string errors;
    errors.swap(pending_errors);
    for (GLenum code = glGetError(); code != GL_NO_ERROR; code = glGetError())
        errors += (errors.empty() ? "glGetError " : "; glGetError ") + std::to_string(code);
    if (!errors.empty()) throw BackendError(std::string("OpenGL error in ") + what + ": " + errors);
}

}  // namespace hyvox::gl
