#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The main job on a fresh Debian 12 machine: install the packages, build hyvox, then let a
# headless Blender voxelize a demo scene (Stanford bunny + Suzanne, then Spot with its
# texture's colour and Sponza with its vertex colours, then a twisting Suzanne rendered
# through Live with no bake step) with the add-on. Writes out/demo/: the .blend, the .vdb
# files and the Cycles renders render.png, render_colour.png, render_colour_sponza.png and
# render_live.png (three frames side by side); prints the stats.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/install_deps.sh
# Debian's cmake/ctest and python3 first: a pyenv (or other) python3 earlier on PATH would
# otherwise become the Python home of Debian's Blender when ctest starts it.
export PATH="/usr/bin:/bin:$PATH"
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build -j "$(nproc)"
blender -b --factory-startup --python demo/run_demo.py -- --build build --output out/demo "$@"
