// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Command-line helper shared by the benchmark programs (never part of the library, so a
// usage error may end the process).
#include <cstdio>
#include <cstdlib>
#include <string>

namespace hyvox::bench {

// The value that follows the option argv[a], advancing a past it; a missing value prints
// "<option> needs a value" and exits with status 2.
inline std::string optionValue(int argc, char** argv, int& a) {
    if (a + 1 >= argc) {
        std::fprintf(stderr, "%s needs a value\n", argv[a]);
        std::exit(2);
    }
    return argv[++a];
}

}  // namespace hyvox::bench
