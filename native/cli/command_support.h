// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// What every `hyvox` command needs around the library calls: Ctrl-C as an Interrupter, a
// whole-run thread limit, an early check of output paths, and wall-clock milliseconds.
#include <tbb/global_control.h>

#include <atomic>
#include <chrono>
#include <memory>
#include <string>

#include "hyvox/interrupter.h"

namespace hyvox::cli {

class StopFlagInterrupter final : public Interrupter {
public:
    explicit StopFlagInterrupter(const std::atomic<bool>& stop) : stop_(stop) {}
    bool wasInterrupted(int) override { return stop_.load(std::memory_order_relaxed); }

private:
    const std::atomic<bool>& stop_;
};

// --threads bounds the whole run (the .vdb tree is also built in parallel), not only the
// backend; null when threads is 0 (all cores).
std::unique_ptr<tbb::global_control> limitThreads(int threads);

// Fails before the (possibly long) voxelization when an output could not be written anyway:
// a missing folder, a folder, a device, FIFO or socket, a symlink to nothing (a symlink to a
// regular file is followed: the file is replaced, the link kept). The writers still check
// everything themselves; this only saves the wait.
void checkOutputFolder(const std::string& path, const char* what);

// Everything checkOutputFolder checks for -o and --stats-json (either may be empty: not
// given), and that neither is the input mesh nor both the same file: a UsageError.
void checkOutputPaths(const std::string& mesh, const std::string& output, const std::string& stats_json);

double msSince(std::chrono::steady_clock::time_point start);

}  // namespace hyvox::cli
