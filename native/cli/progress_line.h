// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The progress of a long run on stderr: "hyvox: voxelize  42%" for each stage the library
// starts (voxelize, write). On a terminal one line is rewritten in place; elsewhere (--progress
// into a pipe or a log) each new whole percent is a line of its own, so a log reads as a tail.
// It is also the command's Interrupter: Ctrl-C (the stop flag) cancels at the next check.
#include <atomic>
#include <cstdio>
#include <mutex>
#include <string>

#include "hyvox/interrupter.h"

namespace hyvox::cli {

class ProgressLine final : public Interrupter {
public:
    // out null: no progress is shown, only the stop flag is checked. in_place: rewrite one
    // line with '\r' (a terminal).
    ProgressLine(const std::atomic<bool>& stop, std::FILE* out, bool in_place);
    ~ProgressLine() override;
    ProgressLine(const ProgressLine&) = delete;
    ProgressLine& operator=(const ProgressLine&) = delete;

    void start(const char* name) override;
    void end() override;
    bool wasInterrupted(int percent = -1) override;

private:
    void finishLine();  // caller holds mutex_

    const std::atomic<bool>& stop_;
    std::FILE* out_;
    bool in_place_;
    std::mutex mutex_;
    std::string stage_;
    // Workers report out of order: only a higher percent than the last shown is printed.
    std::atomic<int> shown_{-1};
    bool line_open_ = false;  // in_place: a line without its newline is on the terminal
};

struct Arguments;

// The command's interrupter: progress on stderr when it is a terminal or --progress asks for
// it, none with --quiet.
ProgressLine progressFor(const Arguments& args, const std::atomic<bool>& stop);

}  // namespace hyvox::cli
