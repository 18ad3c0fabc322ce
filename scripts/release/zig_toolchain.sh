#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Writes the compiler wrappers, a CMake toolchain file and a meson cross file that build
# for PLATFORM with zig (`ziglang` from PyPI), into DIR:
#   scripts/release/zig_toolchain.sh PLATFORM DIR ZIG PREFIX
# ZIG: the zig program; PREFIX: the folder the platform's libraries are installed in (the
# only place CMake looks for libraries). DIR/bin/{cc,c++,ar,ranlib}, DIR/toolchain.cmake,
# DIR/meson-cross.ini. A wrapper is rewritten only when its text changes, so ccache, which
# checks the compiler by its time stamp, sees the same compiler from one release to the next.
set -euo pipefail
if [ $# -ne 4 ]; then
  echo "usage: $0 PLATFORM DIR ZIG PREFIX" >&2
  exit 2
fi
platform=$1 dir=$2 zig=$3 prefix=$4
source "$(dirname "$0")/platforms.sh"
platform_facts "$platform"   # zig_target, cmake_system, cmake_processor, meson_system, meson_cpu

mkdir -p "$dir/bin"
zig_version=$("$zig" version)
write_if_changed() {  # write_if_changed FILE (text on stdin)
  local text
  text=$(cat)
  if [ ! -f "$1" ] || [ "$(cat "$1")" != "$text" ]; then
    printf '%s\n' "$text" > "$1"
  fi
}
for tool in cc c++; do
  write_if_changed "$dir/bin/$tool" <<WRAPPER
#!/bin/sh
# zig $zig_version, $tool for $zig_target
exec "$zig" $tool -target $zig_target "\$@"
WRAPPER
done
for tool in ar ranlib; do
  write_if_changed "$dir/bin/$tool" <<WRAPPER
#!/bin/sh
# zig $zig_version $tool
exec "$zig" $tool "\$@"
WRAPPER
done
chmod +x "$dir"/bin/*

write_if_changed "$dir/toolchain.cmake" <<CMAKE
# Written by scripts/release/zig_toolchain.sh: $platform with zig $zig_version ($zig_target).
set(CMAKE_SYSTEM_NAME $cmake_system)
set(CMAKE_SYSTEM_PROCESSOR $cmake_processor)
set(CMAKE_C_COMPILER "$dir/bin/cc")
set(CMAKE_CXX_COMPILER "$dir/bin/c++")
set(CMAKE_AR "$dir/bin/ar" CACHE FILEPATH "zig ar")
set(CMAKE_RANLIB "$dir/bin/ranlib" CACHE FILEPATH "zig ranlib")
# Libraries come from PREFIX only, never from this machine's /usr/lib; headers and CMake
# packages may also come from the machine (Python's headers, pybind11's CMake files).
set(CMAKE_FIND_ROOT_PATH "$prefix")
set(CMAKE_PREFIX_PATH "$prefix")
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE BOTH)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE BOTH)
set(ENV{PKG_CONFIG_LIBDIR} "$prefix/lib/pkgconfig")
# Bare library names in the packages' link interfaces (assimp's -lminizip) are found there too.
# zig links its C++ runtime (libc++) statically into every binary; what a shared object
# exports is its version script's (hyvox_export_only in CMakeLists.txt).
set(CMAKE_EXE_LINKER_FLAGS_INIT "-L$prefix/lib")
set(CMAKE_SHARED_LINKER_FLAGS_INIT "-L$prefix/lib")
set(CMAKE_MODULE_LINKER_FLAGS_INIT "-L$prefix/lib")
CMAKE

write_if_changed "$dir/meson-cross.ini" <<MESON
[binaries]
c = '$dir/bin/cc'
cpp = '$dir/bin/c++'
ar = '$dir/bin/ar'
strip = 'true'
pkg-config = 'pkg-config'

[properties]
pkg_config_libdir = '$prefix/lib/pkgconfig'

[host_machine]
system = '$meson_system'
cpu_family = '$meson_cpu'
cpu = '$meson_cpu'
endian = 'little'
MESON
