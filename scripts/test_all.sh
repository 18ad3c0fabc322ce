#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Sets up a fresh Debian 12 or 13 machine and runs every hyvox test:
#   1. a Release build with warnings as errors: all native, Python and headless-Blender tests,
#      plus the self-contained wheel and Blender extension, checked in a clean venv and in
#      official Blender releases from PyPI for the machine's Python (pinned venvs under
#      build/venv/: 4.5 LTS and 5.0 with Python 3.11 on Debian 12, 5.1 and 5.3 with 3.13 on 13);
#   2. an AddressSanitizer + UndefinedBehaviorSanitizer build of the native code: the native tests;
#   3. the linters and format checks (scripts/lint.sh: ruff, clang-tidy, clang-format).
# GL tests run on whatever EGL device is there (Mesa llvmpipe without a GPU); none skip.
set -euo pipefail
cd "$(dirname "$0")/.."
# section TITLE: a heading with the seconds since the start, so a log shows where the time went.
section() { echo "== [${SECONDS} s] $1"; }

section "Debian packages and the pinned venvs"
bash scripts/install_deps.sh
bash scripts/setup_venvs.sh build/venv
# Debian's cmake/ctest and python3 first: a pyenv (or other) python3 earlier on PATH would
# otherwise become the Python home of Debian's Blender when ctest starts it.
export PATH="/usr/bin:/bin:$PATH"

jobs=$(nproc)
section "Release build (-Werror)"
# ccache with the source root as base: the wheel's own CMake build (build-wheel/) compiles
# the same sources with the same flags and, relative to its folder, the same paths, so it
# takes the Release build's objects from the cache instead of compiling them again.
export CCACHE_BASEDIR="$PWD"
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DHYVOX_WERROR=ON -DHYVOX_WHEEL=ON \
  -DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache
cmake --build build -j "$jobs"
section "Release tests"
ctest --test-dir build --output-on-failure -j "$jobs"

section "ASan + UBSan build of the native code (-Werror)"
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=Release -DHYVOX_SANITIZE=ON -DHYVOX_WERROR=ON \
  -DHYVOX_BUILD_PYTHON=OFF -DHYVOX_BUILD_BENCH=OFF
cmake --build build-asan -j "$jobs"
section "ASan + UBSan tests"
# Mesa's drivers are not instrumented and keep process-lifetime allocations: leak checks off.
ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --test-dir build-asan --output-on-failure -j "$jobs"

section "Linters and format checks: ruff, clang-tidy, clang-format (any finding fails)"
bash scripts/lint.sh build

section "libFuzzer (clang, ASan + UBSan): the PLY and OBJ readers 60 s each, STL, OFF, glTF and the FBX check 20 s, the assimp formats, gzip input, voxelize and sdf 30 s, solid 45 s; any finding fails"
bash scripts/fuzz_readers.sh
section "done"
