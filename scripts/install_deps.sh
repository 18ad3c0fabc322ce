#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Installs the Debian 12 packages hyvox builds, tests and runs with. Safe to re-run:
# it asks apt only for what is missing.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libopenvdb-dev libboost-dev libimath-dev libtbb-dev zlib1g-dev   # OpenVDB headers need Boost
  libblosc-dev                                                      # .vdb leaf compression (OpenVDB's own)
  libassimp-dev libpng-dev                                          # mesh and image reading
  libepoxy-dev libegl-dev libegl-mesa0 libgl1-mesa-dri              # headless GL (Mesa llvmpipe)
  pybind11-dev python3-dev python3-numpy python3-pytest python3-openvdb python3-pil  # PIL: the attribute oracle reads textures
  python3-venv ccache                                               # wheel + bpy venvs; the wheel's build reuses objects
  libgtest-dev clang                                                 # clang: libFuzzer for the mesh-reader fuzzing
  blender xvfb xauth                                                # add-on tests (modal path in a window)
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install_deps: all ${#packages[@]} packages present"
  exit 0
fi
echo "install_deps: installing ${missing[*]}"
SUDO=""
[ "$(id -u)" -ne 0 ] && SUDO="sudo"
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${missing[@]}"
