#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Builds the libraries hyvox's release links for PLATFORM, static and position-independent,
# from the pinned sources (sources.txt), with zig, once, into a cache outside the repo:
#   scripts/release/build_deps.sh PLATFORM CACHE ZIG
# CACHE/sources holds the tarballs; the libraries go to CACHE/PLATFORM-KEY/prefix, KEY being
# a hash of the pinned versions, these recipes, the toolchain script and zig's version, so a
# change to any of them builds a new prefix and a second release reuses the first's. Each
# library is stamped when installed: an interrupted build resumes with the next one. Prints
# the prefix on its last line. Logs: CACHE/PLATFORM-KEY/logs/NAME.log.
set -euo pipefail
if [ $# -ne 3 ]; then
  echo "usage: $0 PLATFORM CACHE ZIG" >&2
  exit 2
fi
platform=$1 cache=$(realpath -m "$2") zig=$3
here=$(cd "$(dirname "$0")" && pwd)
jobs=$(nproc)

key=$( (cat "$here/sources.txt" "$here/build_deps.sh" "$here/zig_toolchain.sh" "$here/platforms.sh" \
         "$here/openvdb_version_header.cmake"; "$zig" version; echo "$platform") | sha256sum | cut -c1-12)
root="$cache/$platform-$key"
prefix="$root/prefix"
mkdir -p "$prefix/include" "$prefix/lib" "$root/logs" "$root/stamps"
export ZIG_GLOBAL_CACHE_DIR="$cache/zig-cache"
bash "$here/zig_toolchain.sh" "$platform" "$root/toolchain" "$zig" "$prefix"
toolchain="$root/toolchain/toolchain.cmake"
bash "$here/fetch_sources.sh" "$cache/sources"

tarball() {  # tarball PACKAGE: the pinned file of PACKAGE
  awk -v p="$1" '$1 == p { print $3 }' "$here/sources.txt"
}
unpack() {  # unpack PACKAGE: a fresh copy of PACKAGE's sources; prints its folder
  local work="$root/src/$1"
  rm -rf "$work" && mkdir -p "$work"
  tar -C "$work" -xf "$cache/sources/$(tarball "$1")"
  echo "$work/$(ls "$work" | head -1)"
}
cmake_install() {  # cmake_install SOURCE_DIR [cmake -D...]: configure, build, install to the prefix
  local source_dir=$1 build_dir
  shift
  build_dir="$source_dir/../build"
  cmake -S "$source_dir" -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_TOOLCHAIN_FILE="$toolchain" -DCMAKE_INSTALL_PREFIX="$prefix" \
    -DCMAKE_INSTALL_LIBDIR=lib -DCMAKE_POSITION_INDEPENDENT_CODE=ON -DBUILD_SHARED_LIBS=OFF \
    -DCMAKE_POLICY_VERSION_MINIMUM=3.5 "$@"   # CMake 4 refuses the older libraries' minimums
  cmake --build "$build_dir" -j "$jobs"
  cmake --install "$build_dir"
}

build_zlib() {
  local src
  src=$(unpack zlib)
  # zlib's own configure: its CMake file wants win32/zlib1.rc, which Debian's repack removes.
  (cd "$src" && CC="$root/toolchain/bin/cc" AR="$root/toolchain/bin/ar" CFLAGS="-O2 -fPIC" \
     ./configure --static --prefix="$prefix" --libdir="$prefix/lib" && make -j "$jobs" install)
  # minizip, for assimp's zip-based formats: zlib's contrib, as Debian's libminizip builds it.
  mkdir -p "$prefix/include/minizip" "$prefix/lib/pkgconfig" "$src/minizip-build"
  (cd "$src/minizip-build" &&
   for c in ioapi unzip zip; do "$root/toolchain/bin/cc" -O2 -fPIC -I"$prefix/include" -c "$src/contrib/minizip/$c.c" || exit 1; done &&
   "$root/toolchain/bin/ar" rcs "$prefix/lib/libminizip.a" ioapi.o unzip.o zip.o)
  cp "$src"/contrib/minizip/{ioapi,unzip,zip}.h "$prefix/include/minizip/"
  cat > "$prefix/lib/pkgconfig/minizip.pc" <<PC
prefix=$prefix
Name: minizip
Description: zlib's minizip (contrib/minizip)
Version: 1.1
Requires.private: zlib
Libs: -L\${prefix}/lib -lminizip -lz
Cflags: -I\${prefix}/include/minizip
PC
}
build_lz4() {
  cmake_install "$(unpack lz4)/build/cmake" -DLZ4_BUILD_CLI=OFF -DLZ4_BUILD_LEGACY_LZ4C=OFF \
    -DBUILD_STATIC_LIBS=ON
}
build_blosc() {
  # The .vdb writer and reader use blosc's lz4 codec, as OpenVDB does (zlib for blosc's own).
  cmake_install "$(unpack c-blosc)" -DBUILD_SHARED=OFF -DBUILD_STATIC=ON -DBUILD_TESTS=OFF \
    -DBUILD_BENCHMARKS=OFF -DBUILD_FUZZERS=OFF -DPREFER_EXTERNAL_LZ4=ON -DPREFER_EXTERNAL_ZLIB=ON \
    -DDEACTIVATE_SNAPPY=ON -DDEACTIVATE_ZSTD=ON
}
build_png() {
  cmake_install "$(unpack libpng1.6)" -DPNG_SHARED=OFF -DPNG_STATIC=ON -DPNG_TESTS=OFF
  rm -f "$prefix"/bin/png-fix-itxt "$prefix"/bin/pngfix
}
build_tbb() {
  # Static: each of the module, the CLI and the GL plugin holds its own copy with its own
  # C++ runtime, so no exception or std:: object crosses between two runtimes.
  cmake_install "$(unpack onetbb)" -DTBB_TEST=OFF -DTBB_EXAMPLES=OFF -DTBB_STRICT=OFF \
    -DTBBMALLOC_BUILD=OFF -DTBB_ENABLE_IPO=OFF
}
build_khronos_headers() {
  # EGL/eglplatform.h and KHR/khrplatform.h, which libepoxy's headers include: Mesa's copies.
  local work="$root/src/mesa"
  rm -rf "$work" && mkdir -p "$work"
  tar -C "$work" -xf "$cache/sources/$(tarball mesa)" --wildcards '*/include/EGL/*' '*/include/KHR/*'
  cp -r "$work"/*/include/EGL "$work"/*/include/KHR "$prefix/include/"
}
build_epoxy() {
  local src
  src=$(unpack libepoxy)
  CFLAGS="-I$prefix/include" meson setup "$src/../build" "$src" --cross-file "$root/toolchain/meson-cross.ini" \
    --prefix "$prefix" --libdir lib --buildtype release -Ddefault_library=static -Db_staticpic=true \
    -Degl=yes -Dglx=no -Dx11=false -Dtests=false -Ddocs=false
  ninja -C "$src/../build" -j "$jobs" install
}
build_assimp() {
  local src
  src=$(unpack assimp)
  # Debian's repack takes out the copies of utfcpp and stb that assimp keeps in contrib/;
  # put back Debian's own packages of them where assimp's CMake looks.
  mkdir -p "$src/contrib/utf8cpp/source" "$src/contrib/stb" "$root/src/utfcpp"
  dpkg-deb -x "$cache/sources/$(tarball libutfcpp-dev)" "$root/src/utfcpp"
  cp -r "$root"/src/utfcpp/usr/include/utf8cpp/* "$src/contrib/utf8cpp/source/"
  tar -C "$root/src" -xf "$cache/sources/$(tarball libstb)" --wildcards '*/stb_image.h'
  cp "$root"/src/libstb*/stb_image.h "$src/contrib/stb/"
  # Reading only: hyvox's reader program imports, it never exports.
  cmake_install "$src" -DASSIMP_BUILD_TESTS=OFF -DASSIMP_BUILD_ASSIMP_TOOLS=OFF -DASSIMP_BUILD_ZLIB=OFF \
    -DASSIMP_NO_EXPORT=ON -DASSIMP_WARNINGS_AS_ERRORS=OFF -DASSIMP_BUILD_DRACO=OFF \
    -DASSIMP_INSTALL_PDB=OFF -DASSIMP_DOUBLE_PRECISION=OFF
}
build_imath() {
  cmake_install "$(unpack imath)" -DBUILD_TESTING=OFF -DPYTHON=OFF -DIMATH_INSTALL_PKG_CONFIG=ON
}
build_boost_headers() {
  # OpenVDB's headers include a few of Boost's (header-only) libraries.
  local work="$root/src/boost"
  rm -rf "$work" && mkdir -p "$work"
  # The tarball is Boost's modular tree: each library's headers in libs/NAME/include/boost/.
  tar -C "$work" -xf "$cache/sources/$(tarball boost1.74)" --wildcards '*/include/boost/*'
  rm -rf "$prefix/include/boost"
  mkdir -p "$prefix/include/boost"
  find "$work" -type d -path '*/include/boost' -exec cp -r {}/. "$prefix/include/boost/" \;
}
build_fast_float_headers() {
  local src
  src=$(unpack fast-float)
  rm -rf "$prefix/include/fast_float"
  cp -r "$src/include/fast_float" "$prefix/include/"
}
build_openvdb_headers() {
  # The module and the command use OpenVDB's headers only (the library serves the tests).
  local src
  src=$(unpack openvdb)
  rm -rf "$prefix/include/openvdb"
  (cd "$src/openvdb" && find openvdb -name '*.h' -exec install -D -m 644 {} "$prefix/include/{}" \;)
  cmake -DIN="$src/openvdb/openvdb/version.h.in" -DOUT="$prefix/include/openvdb/version.h" \
    -DCMAKE_LISTS="$src/CMakeLists.txt" -P "$here/openvdb_version_header.cmake"
}

for dep in zlib lz4 blosc png tbb khronos_headers epoxy assimp imath boost_headers fast_float_headers openvdb_headers; do
  [ -f "$root/stamps/$dep" ] && continue
  echo "build_deps: $platform: $dep (log: $root/logs/$dep.log)" >&2
  start=$SECONDS
  # A subshell of its own, outside any condition, so that set -e stops the recipe at its
  # first failing command.
  set +e
  (set -ex; "build_$dep") > "$root/logs/$dep.log" 2>&1
  status=$?
  set -e
  if [ $status -ne 0 ]; then
    echo "build_deps: $dep failed; the end of its log:" >&2
    tail -30 "$root/logs/$dep.log" >&2
    exit 1
  fi
  echo "$((SECONDS - start))" > "$root/stamps/$dep"
done
rm -rf "$root/src"
echo "$prefix"
