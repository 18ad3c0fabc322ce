// SPDX-License-Identifier: GPL-3.0-or-later
// hyvox_assimp_reader: the program hyvox starts to read a mesh file through assimp
// (assimp_reader.h), so that whatever assimp does with the file ends this process and not the
// one that asked. It reads one file and writes the mesh, or why there is none, to its
// standard output (mesh_wire.h). Not meant to be run by hand.
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <new>
#include <string>
#include <vector>

#include "hyvox/errors.h"
#include "mesh_io/assimp_import.h"
#include "mesh_io/mesh_wire.h"

namespace {

using namespace hyvox;

bool writeAll(const std::string& bytes) {
    std::size_t at = 0;
    while (at < bytes.size()) {
        const ssize_t n = ::write(1, bytes.data() + at, bytes.size() - at);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return false;
        at += std::size_t(n);
    }
    return true;
}

// assimp's progress steps, passed on; the process is never asked to stop (it is ended).
class ProgressToParent final : public Interrupter {
public:
    bool wasInterrupted(int percent) override {
        if (percent >= 0 && percent != last_) {
            last_ = percent;
            writeAll(mesh_io::wire::progressMessage(percent));
        }
        return false;
    }

private:
    int last_ = -1;
};

std::vector<char> readStandardInput() {
    std::vector<char> bytes;
    char chunk[1 << 16];
    for (;;) {
        const ssize_t n = ::read(0, chunk, sizeof chunk);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) break;
        bytes.insert(bytes.end(), chunk, chunk + n);
    }
    return bytes;
}

// The data segments this process holds already (VmData: its heap and private writable
// mappings), 0 when /proc does not say. Under AddressSanitizer they include its shadow memory,
// terabytes of address space reserved before main.
std::uint64_t dataBytesHeld() {
    std::FILE* status = std::fopen("/proc/self/status", "r");
    if (!status) return 0;
    char line[256];
    unsigned long long kib = 0;
    while (std::fgets(line, sizeof line, status))
        if (std::sscanf(line, "VmData: %llu kB", &kib) == 1) break;
    std::fclose(status);
    return std::uint64_t(kib) * 1024;
}

// The limits first: nothing the file makes assimp do may outgrow them or leave a core file.
// The memory limit counts from what the program holds on starting, so that it bounds what the
// file makes assimp allocate, also in a sanitizer build.
void limitThisProcess(std::uint64_t memory_bytes) {
    const std::uint64_t held = dataBytesHeld();
    const rlim_t limit = memory_bytes > RLIM_INFINITY - held ? RLIM_INFINITY : rlim_t(held + memory_bytes);
    const rlimit data{limit, limit};
    ::setrlimit(RLIMIT_DATA, &data);
    const rlimit no_core{0, 0};
    ::setrlimit(RLIMIT_CORE, &no_core);
    // An allocation the limit refuses ends the process with a status that says so.
    std::set_new_handler([] { ::_exit(mesh_io::wire::kExitOutOfMemory); });
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 7 || std::strcmp(argv[1], mesh_io::wire::kProtocol) != 0) {
        std::fprintf(stderr, "hyvox_assimp_reader: started by hyvox to read one mesh file (protocol %s), not by hand\n",
                     mesh_io::wire::kProtocol);
        return mesh_io::wire::kExitUsage;
    }
    // Ended with the process that started it, also when that one is killed.
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (std::to_string(::getppid()) != argv[2]) return mesh_io::wire::kExitUsage;  // it is already gone
    limitThisProcess(std::strtoull(argv[3], nullptr, 10));
    const std::string extension = argv[4], source = argv[5], name = argv[6];
    ProgressToParent progress;
    std::string message;
    try {
        Mesh mesh;
        if (source == "-") {
            const std::vector<char> bytes = readStandardInput();
            mesh = mesh_io::importWithAssimp(bytes.data(), bytes.size(), extension, name, &progress);
        } else {
            mesh = mesh_io::importWithAssimp(source, extension, &progress);
        }
        message = mesh_io::wire::meshMessage(mesh);
    } catch (const std::bad_alloc&) {
        return mesh_io::wire::kExitOutOfMemory;
    } catch (const InvalidInput& e) {
        message = mesh_io::wire::errorMessage(e.what());
    } catch (const std::exception& e) {
        message = mesh_io::wire::errorMessage("cannot read mesh file '" + name + "': " + e.what());
    }
    return writeAll(message) ? 0 : 1;
}
