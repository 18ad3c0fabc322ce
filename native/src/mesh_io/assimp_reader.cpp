// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesh_io/assimp_reader.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/plugin_library.h"
#include "hyvox/errors.h"
#include "hyvox/options.h"
#include "mesh_io/mesh_wire.h"
#include "os/child_process.h"
#include "os/mesh_file_error.h"

namespace hyvox::mesh_io {
namespace {

constexpr const char* kProgram = "hyvox_assimp_reader";
// How often the interrupter and the clock are looked at while the process runs.
constexpr int kPollMs = 20;
// What of the process's standard error is kept for a message (assimp's assertion text).
constexpr std::size_t kErrorTailBytes = 2048;
// Time limit: a base for starting the process and a small file, and a time per MiB that no
// healthy assimp import comes near (docs/mesh-formats.md).
constexpr double kBaseSeconds = 60.0;
constexpr double kSecondsPerMiB = 2.0;

// The last line of what the process wrote to its standard error, for a message.
std::string lastLine(std::string text) {
    while (!text.empty() && (text.back() == '\n' || text.back() == '\r' || text.back() == ' ')) text.pop_back();
    const auto newline = text.find_last_of('\n');
    if (newline != std::string::npos) text = text.substr(newline + 1);
    for (char& c : text)
        if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f) c = '?';
    return text.substr(0, 300);
}

std::string mib(std::uint64_t bytes) { return std::to_string((bytes + (1u << 20) - 1) >> 20) + " MiB"; }

class Run {
public:
    Run(const std::string& path, const AssimpReadLimits& limits, Interrupter* interrupter)
        : path_(path), limits_(limits), interrupter_(interrupter), decoder_(limits.memory_bytes) {}

    Mesh read(const std::string& extension, const std::string& source, const char* input, std::size_t input_size) {
        const std::string program = pluginFile(kProgram, "reading '" + path_ + "'");
        std::unique_ptr<os::ChildProcess> child;
        try {
            child = std::make_unique<os::ChildProcess>(
                program,
                std::vector<std::string>{program, wire::kProtocol, os::ChildProcess::thisProcessId(),
                                         std::to_string(limits_.memory_bytes), extension, source, path_});
        } catch (const std::runtime_error& e) {
            throw BackendError("reading '" + path_ + "' needs the assimp reader process: " + e.what());
        }
        os::ChildProcess::Input left{input, input_size};
        const auto output = [&](const char* bytes, std::size_t size) {
            try {
                decoder_.feed(bytes, size);
            } catch (const wire::StreamError& e) {
                child->kill();
                os::failMeshFile(path_, "the assimp reader sent back no valid mesh (" + e.what + ")");
            }
        };
        const auto errors = [&](const char* bytes, std::size_t size) {
            errors_.append(bytes, size);
            if (errors_.size() > 2 * kErrorTailBytes) errors_.erase(0, errors_.size() - kErrorTailBytes);
        };
        const auto start = std::chrono::steady_clock::now();
        std::optional<os::ChildExit> exit;
        while (child->writing() || !exit) {
            child->exchange(left, output, errors, kPollMs);
            if (!exit && !child->writing()) exit = child->reaped();
            if (interrupter_ && interrupter_->wasInterrupted(decoder_.percent())) {
                child->kill();
                throw Cancelled();
            }
            const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            if (!exit && seconds > limits_.seconds) {
                child->kill();
                char text[160];
                std::snprintf(text, sizeof text,
                              "the assimp reader did not finish within %.3g s (a damaged file that makes it loop?)",
                              limits_.seconds);
                os::failMeshFile(path_, text);
            }
        }
        return outcome(*exit);
    }

private:
    Mesh outcome(const os::ChildExit& exit) {
        if (!exit.signal.empty()) {
            // An allocation that failed at the limit can end in a crash in C code that does not
            // check it: a peak at the limit says which it was.
            if (double(exit.peak_rss_bytes) >= 0.9 * double(limits_.memory_bytes)) outOfMemory();
            const std::string said = lastLine(errors_);
            os::failMeshFile(
                path_, "the assimp reader crashed on it (" + exit.signal + (said.empty() ? "" : ": " + said) + ")");
        }
        if (exit.exit_code == wire::kExitOutOfMemory) outOfMemory();
        if (exit.exit_code != 0) {
            const std::string said = lastLine(errors_);
            os::failMeshFile(path_,
                             "the assimp reader failed on it (exit status " + std::to_string(exit.exit_code) +
                                 (said.empty() ? "" : ": " + said) + ")");
        }
        if (decoder_.error()) throw InvalidInput(*decoder_.error());
        try {
            return decoder_.finish();
        } catch (const wire::StreamError& e) {
            os::failMeshFile(path_, "the assimp reader sent back no valid mesh (" + e.what + ")");
        }
    }

    [[noreturn]] void outOfMemory() const {
        os::failMeshFile(path_,
                         "reading it through assimp needs more than the memory budget of " + mib(limits_.memory_bytes) +
                             " (memory_budget_mib)");
    }

    std::string path_;
    AssimpReadLimits limits_;
    Interrupter* interrupter_;
    wire::Decoder decoder_;
    std::string errors_;
};

}  // namespace

AssimpReadLimits assimpReadLimits(const MeshReadOptions& options, std::uint64_t file_bytes) {
    VoxelizeOptions budget;
    budget.memory_budget_mib = options.memory_budget_mib;
    const double seconds = options.time_limit_s > 0
        ? options.time_limit_s
        : kBaseSeconds + kSecondsPerMiB * double(file_bytes) / double(1 << 20);
    return {budget.memoryBudgetBytes(), seconds};
}

Mesh readWithAssimp(const std::string& path, const std::string& extension, const AssimpReadLimits& limits,
                    Interrupter* interrupter) {
    return Run(path, limits, interrupter).read(extension, path, nullptr, 0);
}

Mesh readWithAssimp(const char* data, std::size_t size, const std::string& extension, const std::string& path,
                    const AssimpReadLimits& limits, Interrupter* interrupter) {
    return Run(path, limits, interrupter).read(extension, "-", data, size);
}

}  // namespace hyvox::mesh_io
