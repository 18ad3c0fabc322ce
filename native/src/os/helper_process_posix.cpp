// SPDX-License-Identifier: GPL-3.0-or-later
#include "os/helper_process.h"

#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <new>

namespace hyvox::os {
namespace {

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

int g_out_of_memory_exit = 1;  // limitThisProcess's exit code (the new handler captures nothing)

}  // namespace

bool endWithParent(const std::string& parent_id) {
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    return std::to_string(::getppid()) == parent_id;
}

void limitThisProcess(std::uint64_t memory_bytes, int exit_code) {
    const std::uint64_t held = dataBytesHeld();
    const rlim_t limit = memory_bytes > RLIM_INFINITY - held ? RLIM_INFINITY : rlim_t(held + memory_bytes);
    const rlimit data{limit, limit};
    ::setrlimit(RLIMIT_DATA, &data);
    const rlimit no_core{0, 0};
    ::setrlimit(RLIMIT_CORE, &no_core);
    g_out_of_memory_exit = exit_code;
    std::set_new_handler([] { ::_exit(g_out_of_memory_exit); });
}

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

bool writeStandardOutput(const std::string& bytes) {
    std::size_t at = 0;
    while (at < bytes.size()) {
        const ssize_t n = ::write(1, bytes.data() + at, bytes.size() - at);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return false;
        at += std::size_t(n);
    }
    return true;
}

}  // namespace hyvox::os
