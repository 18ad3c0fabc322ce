// SPDX-License-Identifier: GPL-3.0-or-later
#include "command_support.h"

#include <tbb/task_arena.h>

#include <filesystem>

#include "cli_args.h"
#include "hyvox/errors.h"
#include "hyvox/stats_json.h"  // checkOutputPath

namespace hyvox::cli {

std::unique_ptr<tbb::global_control> limitThreads(int threads) {
    if (threads <= 0) return nullptr;
    return std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
}

namespace {

// The same file: one inode (hard links, symlinks, other spellings of an existing file), or
// for a file not there yet, the same path once "..", "." and symlinked folders are resolved.
bool sameFile(const std::string& a, const std::string& b) {
    namespace fs = std::filesystem;
    std::error_code error;
    if (fs::equivalent(fs::path(a), fs::path(b), error) && !error) return true;
    const fs::path ca = fs::weakly_canonical(fs::path(a), error);
    if (error) return false;
    const fs::path cb = fs::weakly_canonical(fs::path(b), error);
    return !error && ca == cb;
}

}  // namespace

void checkOutputPaths(const std::string& mesh, const std::string& output, const std::string& stats_json) {
    if (!output.empty() && sameFile(output, mesh))
        throw UsageError("-o '" + output + "' is the input mesh '" + mesh + "'; refusing to overwrite it");
    if (!stats_json.empty() && sameFile(stats_json, mesh))
        throw UsageError("--stats-json '" + stats_json + "' is the input mesh '" + mesh +
                         "'; refusing to overwrite it");
    if (!output.empty() && !stats_json.empty() && sameFile(output, stats_json))
        throw UsageError("--stats-json '" + stats_json + "' and -o '" + output +
                         "' are the same file; the stats would replace the .vdb");
    if (!output.empty()) checkOutputPath(output);
    if (!stats_json.empty()) checkOutputPath(stats_json);
}

void initializeThreadPool() {
    // The arena goes, the pool's set-up stays for the process. No work is spawned: a worker
    // started now would spin looking for some beside the thread that reads.
    tbb::task_arena(tbb::task_arena::automatic).initialize();
}

double msSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

MeshReadOptions meshReadOptions(const Arguments& args) {
    MeshReadOptions options;
    options.memory_budget_mib = args.options.memory_budget_mib;
    return options;
}

}  // namespace hyvox::cli
