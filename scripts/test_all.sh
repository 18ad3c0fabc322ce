#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Sets up a fresh Debian 12 or 13 machine and runs every hyvox test, cheapest verdict first:
#   deps      the Debian packages (scripts/install_deps.sh)
#   lint      ruff, ruff format and clang-format over the tree: seconds, so a slip fails at once
#   build     a Release build with warnings as errors (build/), with the self-contained wheel and
#             Blender extension and the pinned venvs (build/venv/: bpy 4.5 LTS and 5.0 with
#             Python 3.11 on Debian 12, 5.1 and 5.3 with 3.13 on 13)
#   tidy      clang-tidy over every C++ source of that build
#   test      all native, Python and headless-Blender tests of that build, the wheel in a clean
#             venv and in the official Blender releases from PyPI, the farm jobs for real, and
#             the sweeps over every mesh, size and mode (ctest label `sweep`)
#   release   the release (scripts/build_release.sh: dist/, its libraries cached outside the
#             repo) and its tests (tests/release/): glibc 2.28, the CLI archive, each wheel in
#             a clean venv, the extension in the bpy releases of Python 3.11 and 3.13
#   sanitize  one clang build with AddressSanitizer + UndefinedBehaviorSanitizer and libFuzzer's
#             coverage (build-sanitize/): the native tests without the sweeps, whose code paths
#             the other cases reach (tests/native/CMakeLists.txt says which and why)
#   fuzz      the libFuzzer targets of that same build, a fixed time each (scripts/fuzz_readers.sh)
#
#   bash scripts/test_all.sh               every section, in that order (CI runs this)
#   bash scripts/test_all.sh lint tidy     only those sections (each sets up what it needs)
# GL tests run on whatever EGL device is there (Mesa llvmpipe without a GPU); none skip.
set -euo pipefail
cd "$(dirname "$0")/.."
# Debian's cmake/ctest and python3 first: a pyenv (or other) python3 earlier on PATH would
# otherwise become the Python home of Debian's Blender.
export PATH="/usr/bin:/bin:$PATH"
jobs=$(nproc)
all_sections=(deps lint build tidy test release sanitize fuzz)
sections=("$@")
[ ${#sections[@]} -gt 0 ] || sections=("${all_sections[@]}")
for name in "${sections[@]}"; do
  [[ " ${all_sections[*]} " == *" $name "* ]] ||
    { echo "test_all: no section '$name' (sections: ${all_sections[*]})" >&2; exit 2; }
done

# section TITLE: a heading with the seconds since the start, so a log shows where the time went.
section() { echo "== [${SECONDS} s] $1"; }

run_deps() {
  section "deps: Debian packages"
  bash scripts/install_deps.sh
}

run_lint() {
  section "lint: ruff check, ruff format --check, clang-format (any finding fails)"
  bash scripts/lint.sh build ruff format
}

configure_release() {
  bash scripts/setup_venvs.sh build/venv
  # ccache with the source root as base: the wheel's own CMake build (build-wheel/) compiles
  # the same sources with the same flags and, relative to its folder, the same paths, so it
  # takes the Release build's objects from the cache instead of compiling them again.
  export CCACHE_BASEDIR="$PWD"
  cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DHYVOX_WERROR=ON -DHYVOX_WHEEL=ON \
    -DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache
}

run_build() {
  section "build: Release (-Werror), the wheel and the extension, the pinned venvs"
  configure_release
  cmake --build build -j "$jobs"
}

run_tidy() {
  section "tidy: clang-tidy over the Release build's sources (any finding fails)"
  [ -f build/compile_commands.json ] || configure_release
  # The sources include one header the build generates: the plugins' build id.
  cmake --build build --target hyvox_build_id
  bash scripts/lint.sh build tidy
}

run_test() {
  section "test: the Release build's tests"
  [ -f build/CTestTestfile.cmake ] || run_build
  ctest --test-dir build --output-on-failure -j "$jobs" -LE release
}

run_release() {
  section "release: dist/ by scripts/build_release.sh (linux-x64, cp311 + cp313, glibc 2.28)"
  [ -f build/CTestTestfile.cmake ] || run_build
  bash scripts/build_release.sh
  section "release: its tests (tests/release/): the binaries, the CLI archive, the wheels, the extension in bpy 4.5, 5.0, 5.1, 5.3"
  # The venvs of the Python that /usr/bin/python3 is not come from that Python (pyenv's here).
  system=$(/usr/bin/python3 -c 'import sys; print("%d.%d" % sys.version_info[:2])')
  for version in 3.11 3.13; do
    [ "$version" = "$system" ] && continue
    tag=py${version/./}
    names=(wheel-test $(cd "scripts/requirements/$tag" && ls bpy*.txt | sed 's/\.txt$//'))
    bash scripts/setup_venvs.sh --python "$(bash scripts/find_python.sh "$version")" "build/venv/$tag" "${names[@]}"
  done
  cmake -S . -B build -DHYVOX_RELEASE_DIR="$PWD/dist" >/dev/null
  ctest --test-dir build --output-on-failure -j "$jobs" -L release
}

run_sanitize() {
  section "sanitize: clang ASan + UBSan + libFuzzer coverage build (-Werror)"
  # Coverage for libFuzzer is compiled into the whole build (HYVOX_FUZZ), so the fuzzers link
  # the very libraries the sanitizer tests run: one build serves both.
  cmake -S . -B build-sanitize -G Ninja -DCMAKE_BUILD_TYPE=Release -DHYVOX_SANITIZE=ON \
    -DHYVOX_FUZZ=ON -DHYVOX_WERROR=ON -DHYVOX_BUILD_PYTHON=OFF -DHYVOX_BUILD_BENCH=OFF \
    -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++
  cmake --build build-sanitize -j "$jobs"
  section "sanitize: the native tests under ASan + UBSan, the sweeps left to the Release build"
  # Mesa's drivers are not instrumented and keep process-lifetime allocations: leak checks off.
  # The layering tests compile programs (which headers and symbols a target reaches): they
  # check the build's structure, which the Release build's run has checked, not code that runs.
  ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    ctest --test-dir build-sanitize --output-on-failure -j "$jobs" -LE "sweep|layering"
}

run_fuzz() {
  section "fuzz: libFuzzer (ASan + UBSan): PLY and OBJ readers 60 s each, STL, OFF, glTF and the FBX check 20 s, the assimp formats, gzip input, voxelize and sdf 30 s, solid 45 s; any finding fails"
  [ -f build-sanitize/build.ninja ] || run_sanitize
  bash scripts/fuzz_readers.sh build-sanitize
}

for name in "${sections[@]}"; do
  "run_$name"
done
section "done: ${sections[*]}"
