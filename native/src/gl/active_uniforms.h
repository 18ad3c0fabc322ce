// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Setting uniforms by their fixed locations (shaders/*/bindings.glsl) on the programs that
// use them. Only active uniforms may be set: a location the compiler dropped is an error in
// GL, and which ones it drops depends on the defines and on the driver.
#include <epoxy/gl.h>

#include <cstdint>
#include <initializer_list>

#include "gl/gl_objects.h"

namespace hyvox::gl {

// A linked program and the locations (bit i: location i, below 64) of its active uniforms,
// found once.
class ActiveProgram {
public:
    ActiveProgram() = default;
    explicit ActiveProgram(const Program& program);

    const Program* program() const { return program_; }
    bool uses(GLint location) const { return location >= 0 && location < 64 && (active_ >> location & 1u); }

private:
    const Program* program_ = nullptr;
    std::uint64_t active_ = 0;
};

// Calls set(program id) for each of `programs` (null or empty ones skipped) that uses
// `location`; set calls glProgramUniform*.
template <typename Set>
void setUniform(std::initializer_list<const ActiveProgram*> programs, GLint location, const Set& set) {
    for (const ActiveProgram* p : programs)
        if (p && p->program() && p->uses(location)) set(p->program()->id());
}

}  // namespace hyvox::gl
