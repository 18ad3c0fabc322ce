// SPDX-License-Identifier: GPL-3.0-or-later
// A consumer of hyvox_lib that includes a GL layer's header: it must not compile unless it
// links that layer itself (CMakeLists.txt here).
#include <cstdio>

#include "gl/device_limits.h"

int main() { return std::printf("%llu\n", static_cast<unsigned long long>(hyvox::gl::maxStorageBlockBytes(""))) < 0; }
