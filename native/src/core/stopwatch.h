// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <chrono>

namespace hyvox {

// Wall-clock milliseconds since construction or the last restart().
class Stopwatch {
public:
    Stopwatch() : start_(Clock::now()) {}
    double elapsedMs() const { return std::chrono::duration<double, std::milli>(Clock::now() - start_).count(); }
    double restart() {
        const double ms = elapsedMs();
        start_ = Clock::now();
        return ms;
    }

private:
    using Clock = std::chrono::steady_clock;
    Clock::time_point start_;
};

}  // namespace hyvox
