// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// What every `hyvox` command needs around the library calls: Ctrl-C as an Interrupter, a
// whole-run thread limit, an early check of output paths, and wall-clock milliseconds.
#include <tbb/global_control.h>

#include <atomic>
#include <chrono>
#include <memory>
#include <string>

#include "cli_args.h"
#include "hyvox/interrupter.h"
#include "hyvox/mesh_io.h"

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

// Fails before the (possibly long) voxelization when -o or --stats-json (either may be
// empty: not given) could not be written anyway (hyvox::checkOutputPath, InvalidInput), or is
// the input mesh, or both are the same file (UsageError).
void checkOutputPaths(const std::string& mesh, const std::string& output, const std::string& stats_json);

// Sets up TBB's thread pool as its first use would. That is a noticeable part of a small run
// (TBB loads libtbbmalloc, looks for optional libraries along the library path and reads
// /proc): a command calls this while another thread reads its input. The workers themselves
// start with the first parallel loop, which costs little (docs/why/startup.md).
void initializeThreadPool();

// The mesh is read within the run's memory budget (--memory-budget-mib), as it is voxelized.
MeshReadOptions meshReadOptions(const Arguments& args);

double msSince(std::chrono::steady_clock::time_point start);

}  // namespace hyvox::cli
