// SPDX-License-Identifier: GPL-3.0-or-later
// A consumer of hyvox_lib that declares a GL layer's function by hand (no header): it must not
// link unless it links that layer itself, as hyvox_lib holds no GL code (CMakeLists.txt here).
#include <cstdint>
#include <cstdio>
#include <string>

namespace hyvox::gl {
std::uint64_t maxStorageBlockBytes(const std::string& device);  // gl/device_limits.h
}

int main() { return std::printf("%llu\n", static_cast<unsigned long long>(hyvox::gl::maxStorageBlockBytes(""))) < 0; }
