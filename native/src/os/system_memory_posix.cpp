// SPDX-License-Identifier: GPL-3.0-or-later
#include "os/system_memory.h"

#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <string>

namespace hyvox::os {
namespace {

// The cgroup v2 limit of this process's group (a container's memory.max), or 0 for none.
std::uint64_t cgroupLimitBytes() {
    std::ifstream groups("/proc/self/cgroup");
    std::string line, path;
    while (std::getline(groups, line))
        if (line.rfind("0::", 0) == 0) path = line.substr(3);
    if (path.empty()) return 0;
    // The group's own limit, or a parent's: the tightest one on the way up holds.
    std::uint64_t tightest = 0;
    for (;;) {
        std::ifstream max("/sys/fs/cgroup" + path + "/memory.max");
        std::string value;
        if (max >> value && value != "max") {
            const std::uint64_t bytes = std::strtoull(value.c_str(), nullptr, 10);
            if (bytes > 0 && (tightest == 0 || bytes < tightest)) tightest = bytes;
        }
        if (path.empty() || path == "/") break;
        const auto slash = path.find_last_of('/');
        path = slash == std::string::npos || slash == 0 ? "" : path.substr(0, slash);
    }
    return tightest;
}

}  // namespace

std::uint64_t availableMemoryBytes() {
    const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGESIZE);
    std::uint64_t bytes = pages > 0 && page > 0 ? std::uint64_t(pages) * std::uint64_t(page) : 0;
    if (const std::uint64_t limit = cgroupLimitBytes(); limit > 0) bytes = bytes == 0 ? limit : std::min(bytes, limit);
    return bytes;
}

}  // namespace hyvox::os
