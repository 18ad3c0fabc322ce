// SPDX-License-Identifier: GPL-3.0-or-later
#include "progress_line.h"

#include <unistd.h>

#include <cstring>

#include "cli_args.h"

namespace hyvox::cli {

ProgressLine::ProgressLine(const std::atomic<bool>& stop, std::FILE* out, bool in_place)
    : stop_(stop), out_(out), in_place_(in_place) {}

ProgressLine::~ProgressLine() {
    if (!out_) return;
    const std::lock_guard<std::mutex> lock(mutex_);
    finishLine();  // an error message after a cancelled run starts on a line of its own
}

void ProgressLine::start(const char* name) {
    if (!out_) return;
    const std::lock_guard<std::mutex> lock(mutex_);
    finishLine();
    // The library names its runs "hyvox voxelize", "hyvox write": the line already says hyvox.
    const char* prefix = "hyvox ";
    stage_ = std::strncmp(name, prefix, std::strlen(prefix)) == 0 ? name + std::strlen(prefix) : name;
    shown_.store(-1);
}

void ProgressLine::end() {
    if (!out_) return;
    const std::lock_guard<std::mutex> lock(mutex_);
    finishLine();
}

bool ProgressLine::wasInterrupted(int percent) {
    if (out_ && percent >= 0 && percent > shown_.load(std::memory_order_relaxed)) {
        const std::lock_guard<std::mutex> lock(mutex_);
        if (percent > shown_.load()) {
            shown_.store(percent);
            std::fprintf(out_, in_place_ ? "\rhyvox: %s %3d%%" : "hyvox: %s %3d%%\n", stage_.c_str(), percent);
            std::fflush(out_);
            line_open_ = in_place_;
        }
    }
    return stop_.load(std::memory_order_relaxed);
}

void ProgressLine::finishLine() {
    if (line_open_) std::fputc('\n', out_);
    line_open_ = false;
}

ProgressLine progressFor(const Arguments& args, const std::atomic<bool>& stop) {
    const bool terminal = isatty(STDERR_FILENO) == 1;
    const bool show = !args.quiet && (args.progress || terminal);
    return ProgressLine(stop, show ? stderr : nullptr, terminal);
}

}  // namespace hyvox::cli
