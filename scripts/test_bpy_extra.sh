#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The add-on tests in the Blender releases tested on request only, not in CI (the lists in
# scripts/requirements/pyXY/extra/: 4.2, 4.3 and 4.4 on Python 3.11; CI tests 4.5 and 5.0):
# makes their venvs (about 300 MB of download each), builds build/ as scripts/test_all.sh
# does with -DHYVOX_BPY_EXTRA=ON, runs the tests labelled bpy_extra (bpy42_*, bpy43_*,
# bpy44_*), and sets the option back to OFF, so the next full ctest is CI's again.
set -euo pipefail
cd "$(dirname "$0")/.."
export PATH="/usr/bin:/bin:$PATH" CCACHE_BASEDIR="$PWD"
HYVOX_BPY_EXTRA=1 bash scripts/setup_venvs.sh build/venv
configure() {  # configure ON|OFF
  cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DHYVOX_WERROR=ON -DHYVOX_WHEEL=ON \
    -DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache \
    -DHYVOX_BPY_EXTRA="$1" >/dev/null
}
trap 'configure OFF' EXIT
configure ON
cmake --build build -j "$(nproc)"
ctest --test-dir build -L bpy_extra --output-on-failure -j "$(nproc)"
