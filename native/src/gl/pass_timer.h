// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The GPU time of one pass of a GL method: a GL_TIME_ELAPSED query on hardware, or the
// wall clock around glFinish where queries are unreliable (llvmpipe reads ~0 for compute)
// or GlOptions::wall_timing asks for it (gl::GlTuning decides which).
#include "core/stopwatch.h"
#include "gl/gl_objects.h"

namespace hyvox::gl {

class PassTimer {
public:
    explicit PassTimer(bool wall_clock) : wall_clock_(wall_clock) {}

    void begin() {
        if (wall_clock_) glFinish();
        watch_.restart();
        query_.begin();
    }
    // Call before anything that may throw: an open query would break the next pass.
    void end() {
        TimerQuery::end();
        if (wall_clock_) {
            glFinish();
            wall_ms_ = watch_.elapsedMs();
        }
    }
    double milliseconds() const { return wall_clock_ ? wall_ms_ : query_.milliseconds(); }

private:
    bool wall_clock_;
    Stopwatch watch_;
    TimerQuery query_;
    double wall_ms_ = 0;
};

}  // namespace hyvox::gl
