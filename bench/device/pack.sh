#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Makes the folder a lent GPU machine runs from (bench/device/README.md):
#   DEST/bin/bench_device    a Release build, stripped (hyvox's libraries are static in it)
#   DEST/lib/                the shared libraries it needs that a bare machine lacks (ldd),
#                            without glibc and the GL/EGL stack (the .gl debs and the driver)
#   DEST/lib/fallback/       libstdc++ and libgcc_s, used only where the machine has none
#   DEST/meshes/             the Table 1 meshes, gzipped
#   DEST/run.sh, table.py    the driver and the CSV-to-table converter (with bench_results.py)
# then checks that the binary finds every library but the GL ones with LD_LIBRARY_PATH set to
# DEST/lib alone, and prints the size that will travel (the device takes 64 MiB in all).
#   bash bench/device/pack.sh BUILD_DIR DEST [MESH_DIR]
set -euo pipefail
BUILD=${1:?usage: pack.sh BUILD_DIR DEST [MESH_DIR]}
DEST=${2:?usage: pack.sh BUILD_DIR DEST [MESH_DIR]}
MESHES=${3:-$(cd "$(dirname "$0")/../.." && pwd)/../shared/data/meshes}
SRC=$(cd "$(dirname "$0")" && pwd)

grep -q 'CMAKE_BUILD_TYPE:STRING=Release' "$BUILD/CMakeCache.txt" || { echo "pack.sh: $BUILD is not a Release build" >&2; exit 1; }
cmake --build "$BUILD" --target bench_device >/dev/null
rm -rf "$DEST"
mkdir -p "$DEST/bin" "$DEST/lib/fallback" "$DEST/meshes"
strip -o "$DEST/bin/bench_device" "$BUILD/bench/bench_device"
cp "$SRC/run.sh" "$SRC/table.py" "$SRC/../bench_results.py" "$DEST/"

# Libraries the machine provides itself: glibc's, and the GL/EGL/GLX stack (glvnd from the
# .gl debs, the vendor libraries from the driver). libstdc++/libgcc_s go to fallback/.
system='^(linux-vdso|ld-linux|libc|libm|libdl|libpthread|librt|libresolv)\.so'
gl='^(libEGL|libGL|libGLX|libGLdispatch|libOpenGL|libGLES|libX11|libxcb|libXau|libXdmcp)'
ldd "$BUILD/bench/bench_device" | awk '/=>/ {print $1, $3}' | while read -r name path; do
    if [[ $name =~ $system || $name =~ $gl ]]; then continue; fi
    if [[ $name == libstdc++.so.* || $name == libgcc_s.so.* ]]; then
        cp -L "$path" "$DEST/lib/fallback/$name"
    else
        cp -L "$path" "$DEST/lib/$name"
    fi
done

for m in bunny_stanford_69k.ply dragon_stanford_res2_203k.ply.gz sponza_crytek_262k_vcolor.ply.gz \
    dragon_stanford_871k.ply.gz; do
    if [[ $m == *.gz ]]; then cp "$MESHES/$m" "$DEST/meshes/$m"; else gzip -9 -c "$MESHES/$m" >"$DEST/meshes/$m.gz"; fi
done

# Every library resolves from DEST/lib (and the system's glibc); nothing is "not found".
missing=$(env -i PATH=/usr/bin:/bin LD_LIBRARY_PATH="$DEST/lib:$DEST/lib/fallback" ldd "$DEST/bin/bench_device" |
    grep 'not found' || true)
[ -z "$missing" ] || { echo "pack.sh: missing libraries:" >&2; echo "$missing" >&2; exit 1; }
outside=$(env -i PATH=/usr/bin:/bin LD_LIBRARY_PATH="$DEST/lib:$DEST/lib/fallback" ldd "$DEST/bin/bench_device" |
    awk '/=>/ {print $1, $3}' | grep -v " $DEST/" | awk '{print $1}' | tr '\n' ' ')
echo "resolved outside $DEST (glibc and GL, which the machine has): $outside"
usage=$(env -i PATH=/usr/bin:/bin LD_LIBRARY_PATH="$DEST/lib:$DEST/lib/fallback" "$DEST/bin/bench_device" --help 2>&1 || true)
[[ $usage == usage:* ]] || { echo "pack.sh: bench_device does not start: $usage" >&2; exit 1; }
du -sh "$DEST"/*
du -sh "$DEST"
