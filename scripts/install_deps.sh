#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Installs the Debian packages hyvox builds, tests and runs with, on Debian 12 (bookworm)
# or 13 (trixie): one set of names for both (13 keeps OpenVDB 10 and its python3-openvdb,
# so `import pyopenvdb` too; blender is 3.4 on 12, 4.3 on 13; clang is 14 on 12, 19 on 13:
# its libFuzzer runtime, libclang-rt-N-dev, comes in as a Recommends of libclang-common-N-dev,
# which apt installs by default). Safe to re-run: it asks apt only for what is missing.
set -euo pipefail

debian=$(cut -d. -f1 /etc/debian_version 2>/dev/null || echo unknown)
case "$debian" in
  12|13) ;;
  *) echo "install_deps: written for Debian 12 and 13; /etc/debian_version says '$debian':" \
          "package names may differ" >&2 ;;
esac

packages=(
  build-essential cmake ninja-build pkg-config
  libopenvdb-dev libboost-dev libimath-dev libtbb-dev zlib1g-dev   # OpenVDB headers need Boost
  libblosc-dev                                                      # .vdb leaf compression (OpenVDB's own)
  libassimp-dev libpng-dev                                          # mesh and image reading
  libfast-float-dev                                                 # the text readers' numbers
  libepoxy-dev libegl-dev libegl-mesa0 libgl1-mesa-dri              # headless GL (Mesa llvmpipe)
  # python3-dev: the module's build, and quickjs's from its sdist on 3.13 (requirements/py313/farm.txt)
  pybind11-dev python3-dev python3-numpy python3-pytest python3-openvdb python3-pil  # PIL: the attribute oracle reads textures
  python3-venv ccache                                               # wheel + bpy venvs; the wheel's build reuses objects
  strace                                                            # the durable_write test watches fsync/rename calls
  libgtest-dev clang                                                 # clang: libFuzzer for the mesh-reader fuzzing
  doxygen                                                           # the C++ API reference's check (docs/Doxyfile)
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
