// SPDX-License-Identifier: GPL-3.0-or-later
// `hyvox`: every failure becomes a message on stderr and a non-zero exit status
// (2 usage, 1 error, 130 interrupted); nothing escapes main as a crash.
#include <malloc.h>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <exception>
#include <new>
#include <string>
#include <vector>

#include "cli_args.h"
#include "gamma_sweep_command.h"
#include "hyvox/errors.h"
#include "hyvox/version.h"
#include "job_template_command.h"
#include "merge_command.h"
#include "voxelize_command.h"

namespace {

std::atomic<bool> g_stop{false};
static_assert(std::atomic<bool>::is_always_lock_free, "set from a signal handler");

extern "C" void onSignal(int) { g_stop.store(true); }

int fail(const std::string& message, int status) {
    std::fprintf(stderr, "hyvox: error: %s\n", message.c_str());
    return status;
}

}  // namespace

int main(int argc, char** argv) {
    using namespace hyvox;
    // One run, then exit: blocks of 128 KiB to 32 MiB (mesh arrays, per-vertex cells, the
    // .vdb's buffers) come from the heap and go back to it. By default glibc maps each afresh
    // and unmaps it when freed: every page is then faulted in anew and each unmapping
    // interrupts the CPUs of the worker threads (a TLB shootdown); from the heap, a freed
    // block's pages serve the next block. Larger blocks are still mapped.
    // (docs/why/startup.md; the Python module leaves its host's malloc alone.)
    mallopt(M_MMAP_THRESHOLD, 32 << 20);
    mallopt(M_TRIM_THRESHOLD, 64 << 20);
    // Ctrl-C cancels a voxelization between steps; the .vdb is then never written.
    std::signal(SIGINT, onSignal);
    std::signal(SIGTERM, onSignal);
    try {
        if (argc > 1 && std::string(argv[1]) == "job-template") {
            cli::runJobTemplate(std::vector<std::string>(argv + 2, argv + argc));
            return 0;
        }
        const cli::Arguments args = cli::parseArguments(std::vector<std::string>(argv + 1, argv + argc));
        for (const std::string& warning : args.warnings) std::fprintf(stderr, "hyvox: warning: %s\n", warning.c_str());
        switch (args.command) {
            case cli::Command::Help: std::fputs(cli::usageText(args.help_topic).c_str(), stdout); return 0;
            case cli::Command::Version: std::printf("hyvox %s\n", version()); return 0;
            case cli::Command::Voxelize: cli::runVoxelize(args, g_stop); return 0;
            case cli::Command::GammaSweep: cli::runGammaSweep(args, g_stop); return 0;
            case cli::Command::Merge: cli::runMerge(args, g_stop); return 0;
        }
        return 0;
    } catch (const cli::UsageError& e) {
        std::fprintf(stderr, "hyvox: error: %s\n(%s)\n", e.what(), e.hint.c_str());
        return 2;
    } catch (const Cancelled&) {
        return fail("interrupted; nothing was written", 130);
    } catch (const InvalidInput& e) {
        return fail(e.what(), 1);
    } catch (const ResourceError& e) {
        return fail(e.what(), 1);
    } catch (const BackendError& e) {
        return fail(e.what(), 1);
    } catch (const std::bad_alloc&) {
        return fail("out of memory (try a larger voxel size)", 1);
    } catch (const std::exception& e) {
        return fail(std::string("unexpected failure: ") + e.what(), 1);
    } catch (...) {
        return fail("unexpected failure of an unknown kind", 1);
    }
}
