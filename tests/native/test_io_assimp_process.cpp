// SPDX-License-Identifier: GPL-3.0-or-later
// The assimp reader process (src/mesh_io/assimp_reader.h): whatever happens to the process that
// reads the file (it crashes, hangs, runs out of memory, writes garbage or a mesh with bad
// indices, is cancelled), readMesh returns with a clear InvalidInput naming the file (or
// hyvox::Cancelled), and no process is left behind. The fake readers are small shell scripts
// found first through HYVOX_PLUGIN_DIR; the real reader reads the committed files that made
// assimp abort (tests/regressions/meshes/). tests/python/test_mesh_formats.py has the real
// reader's reads, its memory budget and its cancel from another thread.
#include <dirent.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "hyvox/errors.h"
#include "hyvox/mesh_io.h"
#include "mesh_io/mesh_wire.h"
#include "support/temp_dir.h"

namespace fs = std::filesystem;
using hyvox::test::TempDir;

namespace {

// HYVOX_PLUGIN_DIR set for one test, restored after.
class PluginDir {
public:
    explicit PluginDir(const fs::path& folder) {
        if (const char* old = std::getenv("HYVOX_PLUGIN_DIR")) old_ = old;
        ::setenv("HYVOX_PLUGIN_DIR", folder.c_str(), 1);
    }
    ~PluginDir() {
        if (old_.empty())
            ::unsetenv("HYVOX_PLUGIN_DIR");
        else
            ::setenv("HYVOX_PLUGIN_DIR", old_.c_str(), 1);
    }

private:
    std::string old_;
};

// A fake hyvox_assimp_reader: a shell script doing `body`.
fs::path fakeReader(const TempDir& dir, const std::string& body) {
    const fs::path path = dir.write("hyvox_assimp_reader", "#!/bin/sh\n" + body + "\n");
    ::chmod(path.c_str(), 0755);
    return path;
}

// The processes whose parent is this one (from /proc): none may outlive a read.
std::vector<std::string> children() {
    std::vector<std::string> found;
    const std::string me = std::to_string(::getpid());
    DIR* proc = ::opendir("/proc");
    if (!proc) return found;
    while (dirent* entry = ::readdir(proc)) {
        std::ifstream stat(std::string("/proc/") + entry->d_name + "/stat");
        std::string line;
        if (!std::getline(stat, line)) continue;
        // pid (comm) state ppid ...: comm may hold spaces, so read after the last ')'.
        const auto close = line.rfind(')');
        if (close == std::string::npos) continue;
        char state = 0;
        long ppid = 0;
        if (std::sscanf(line.c_str() + close + 1, " %c %ld", &state, &ppid) == 2 && std::to_string(ppid) == me)
            found.push_back(std::string(entry->d_name) + " " + line.substr(0, close + 1) + " " + state);
    }
    ::closedir(proc);
    return found;
}

std::string errorOf(const fs::path& path, const hyvox::MeshReadOptions& options = {},
                    hyvox::Interrupter* interrupter = nullptr) {
    try {
        hyvox::readMesh(path.string(), interrupter, options);
    } catch (const hyvox::InvalidInput& e) {
        return e.what();
    } catch (const hyvox::Cancelled&) {
        return "(cancelled)";
    } catch (const std::exception& e) {
        return std::string("(wrong exception) ") + e.what();
    }
    return "(no error)";
}

#define EXPECT_HAS(TEXT, PART) EXPECT_NE(std::string(TEXT).find(PART), std::string::npos) << (TEXT)

fs::path regressionDir() { return fs::path(HYVOX_REGRESSION_MESHES); }

}  // namespace

TEST(AssimpProcess, FilesThatMadeAssimpAbortAreErrorsHere) {
    // Damaged files on which assimp ends its process with an assertion (SIGABRT): found by
    // tests/damage/damage_meshes.py and the fuzzers, kept as regressions.
    std::size_t seen = 0;
    for (const auto& entry : fs::directory_iterator(regressionDir())) {
        if (entry.path().filename().string().rfind("assimp_abort_", 0) != 0) continue;
        ++seen;
        const std::string message = errorOf(entry.path());
        EXPECT_HAS(message, entry.path().filename().string());
        EXPECT_HAS(message, "the assimp reader crashed on it (SIGABRT: ai_assert failure");
    }
    EXPECT_GT(seen, 0u);
    EXPECT_EQ(children(), std::vector<std::string>{});
}

TEST(AssimpProcess, ACrashOrAnExitIsAnErrorNamingTheFile) {
    TempDir plugins, files;
    const PluginDir use(plugins.path);
    const fs::path mesh = files.write("scene.3mf", "PK");
    fakeReader(plugins, "echo 'ai_assert failure in Something.cpp(12): x != y' >&2\nkill -ABRT $$");
    EXPECT_HAS(errorOf(mesh),
               "mesh file '" + mesh.string() +
                   "': the assimp reader crashed on it (SIGABRT: ai_assert failure in Something.cpp(12): x != y)");
    fakeReader(plugins, "kill -SEGV $$");
    EXPECT_HAS(errorOf(mesh), "the assimp reader crashed on it (SIGSEGV)");
    fakeReader(plugins, "echo 'something went wrong' >&2\nexit 7");
    EXPECT_HAS(errorOf(mesh), "the assimp reader failed on it (exit status 7: something went wrong)");
    fakeReader(plugins, "exit " + std::to_string(hyvox::mesh_io::wire::kExitOutOfMemory));
    EXPECT_HAS(errorOf(mesh), "reading it through assimp needs more than the memory budget of");
    EXPECT_EQ(children(), std::vector<std::string>{});
}

TEST(AssimpProcess, WhatTheProcessSendsIsNotTrusted) {
    TempDir plugins, files;
    const PluginDir use(plugins.path);
    const fs::path mesh = files.write("scene.3mf", "PK");
    fakeReader(plugins, "printf 'garbage'");
    EXPECT_HAS(errorOf(mesh), "the assimp reader sent back no valid mesh (a message of no known kind)");
    fakeReader(plugins, "printf 'P'");  // then nothing
    EXPECT_HAS(errorOf(mesh),
               "the assimp reader sent back no valid mesh (the stream ended before a whole mesh or error)");
    // A well-formed mesh message whose triangle names a vertex past the end.
    hyvox::Mesh bad;
    bad.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    bad.triangles = {0, 1, 3};
    const fs::path bytes = files.write("bad.bin", hyvox::mesh_io::wire::meshMessage(bad));
    fakeReader(plugins, "cat '" + bytes.string() + "'");
    EXPECT_HAS(errorOf(mesh), "the assimp reader sent back no valid mesh (a triangle index past the vertices)");
    // A mesh message declaring more than the budget is refused before anything is allocated.
    std::string huge = hyvox::mesh_io::wire::meshMessage(bad);
    const std::uint64_t vertices = 1ull << 40;
    std::memcpy(&huge[1], &vertices, sizeof vertices);
    fakeReader(plugins, "cat '" + files.write("huge.bin", huge).string() + "'");
    EXPECT_HAS(errorOf(mesh), "the assimp reader sent back no valid mesh (a mesh larger than the memory budget)");
    // Its error message is passed on as it is.
    fakeReader(
        plugins,
        "cat '" +
            files.write("error.bin", hyvox::mesh_io::wire::errorMessage("cannot read mesh file 'x': why")).string() +
            "'");
    EXPECT_EQ(errorOf(mesh), "cannot read mesh file 'x': why");
    EXPECT_EQ(children(), std::vector<std::string>{});
}

TEST(AssimpProcess, AHangEndsAtTheTimeLimit) {
    TempDir plugins, files;
    const PluginDir use(plugins.path);
    const fs::path mesh = files.write("scene.3mf", "PK");
    fakeReader(plugins, "exec sleep 600");
    hyvox::MeshReadOptions options;
    options.time_limit_s = 0.3;
    const auto start = std::chrono::steady_clock::now();
    EXPECT_HAS(errorOf(mesh, options), "the assimp reader did not finish within 0.3 s");
    // Ended at the limit, not when the sleep would have: a bound far above the limit, far
    // below the sleep.
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 300.0);
    EXPECT_EQ(children(), std::vector<std::string>{});
}

TEST(AssimpProcess, CancelEndsTheProcess) {
    TempDir plugins, files;
    const PluginDir use(plugins.path);
    const fs::path mesh = files.write("scene.3mf", "PK");
    fakeReader(plugins, "exec sleep 600");
    // Stops at the fifth question: readMesh's own 0% and four looks while the process runs.
    struct StopAtFifth final : hyvox::Interrupter {
        int asked = 0;
        bool wasInterrupted(int) override { return ++asked >= 5; }
    } stop;
    EXPECT_EQ(errorOf(mesh, {}, &stop), "(cancelled)");
    EXPECT_EQ(stop.asked, 5);
    EXPECT_EQ(children(), std::vector<std::string>{});
}

TEST(AssimpProcess, ReaderOfAnotherProtocolRefusesToRun) {
    // The real program, started by hand (not by hyvox), says what it is and exits.
    const std::string program = (fs::path(HYVOX_ASSIMP_READER)).string();
    const std::string output = program + " 2>&1";
    FILE* run = ::popen(output.c_str(), "r");
    ASSERT_NE(run, nullptr);
    char text[512] = {};
    const std::size_t n = std::fread(text, 1, sizeof text - 1, run);
    const int status = ::pclose(run);
    EXPECT_HAS(std::string(text, n), "started by hyvox to read one mesh file");
    EXPECT_EQ(WEXITSTATUS(status), hyvox::mesh_io::wire::kExitUsage);
}
