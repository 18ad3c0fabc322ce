#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The first GPU run (bench/device/README.md). Runs from the folder pack.sh made (bin/, lib/,
# meshes/, this script), inside a checkout whose root also holds .gl/ (the GL loader .debs).
# Writes under $OUT: table1.csv (one row per method, flushed as made), log.txt (everything
# printed), device.txt (nvidia-smi, CPU, OS), gl_info.txt (EGL devices, GL_RENDERER, ...).
#   OUT=/tmp/out bash .devrun/run.sh               # the full run, about 6 minutes on a GPU
#   REHEARSAL=1 OUT=/tmp/out bash .devrun/run.sh   # a few minutes of it on llvmpipe
# Knobs (environment): ORDER, SCENES, REPEAT, ROW_BUDGET_S, BUDGET_S, TIMEOUT_S, HYVOX_GL_DEVICE.
set -u
HERE=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
ROOT=$(cd "$HERE/.." && pwd)
: "${OUT:?OUT must name the folder for the results}"
mkdir -p "$OUT"
exec > >(tee "$OUT/log.txt") 2>&1
TEE_PID=$!
# Ends the script only after tee has written the last lines (the device collects $OUT and the
# output as soon as the command returns).
finish() {
    exec 1>&- 2>&-
    wait "$TEE_PID" 2>/dev/null
    exit "$1"
}
echo "# run.sh start $(date -u +%FT%TZ) in $HERE"

# The GL loaders (glvnd: libEGL, libOpenGL, libGLdispatch) when the machine lacks them, as
# the device README says; a machine that has them (this one in a rehearsal) is left alone.
if ! ldconfig -p | grep -q 'libEGL.so.1 ' || ! ldconfig -p | grep -q 'libOpenGL.so.0 '; then
    echo "# unpacking the GL loader packages from $ROOT/.gl"
    for f in "$ROOT"/.gl/*.deb; do dpkg -x "$f" /; done
    ldconfig
fi
# The NVIDIA EGL vendor file, when glvnd's own folders lack one (the driver is mounted apart,
# the device README names /usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json).
if ! ls /usr/share/glvnd/egl_vendor.d/*nvidia* /etc/glvnd/egl_vendor.d/*nvidia* >/dev/null 2>&1; then
    vendor=$(ls /usr/local/nvidia/share/glvnd/egl_vendor.d/*nvidia*.json 2>/dev/null | head -1)
    [ -n "$vendor" ] || vendor=$(find /usr/local /usr/share /etc -maxdepth 6 -path '*egl_vendor.d/*nvidia*.json' \
        2>/dev/null | head -1)
    if [ -n "$vendor" ]; then
        export __EGL_VENDOR_LIBRARY_FILENAMES=$vendor
        echo "# __EGL_VENDOR_LIBRARY_FILENAMES=$__EGL_VENDOR_LIBRARY_FILENAMES"
    fi
fi
# The carried libraries first; the driver's folders after them; libstdc++ and libgcc_s only
# where the machine has none (its own are newer than ours).
LIBS=$HERE/lib
for d in /usr/local/nvidia/lib64 /usr/local/nvidia/lib; do [ -d "$d" ] && LIBS=$LIBS:$d; done
ldconfig -p | grep -q 'libstdc++.so.6 ' || LIBS=$LIBS:$HERE/lib/fallback
export LD_LIBRARY_PATH=$LIBS${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
echo "# LD_LIBRARY_PATH=$LD_LIBRARY_PATH"
if ldd "$HERE/bin/bench_device" | grep 'not found'; then echo "# a library is missing (above)"; fi

{
    echo "date=$(date -u +%FT%TZ)"
    echo "host=$(uname -srm)"
    echo "os=$(. /etc/os-release 2>/dev/null && echo "$PRETTY_NAME")"
    echo "cpus=$(nproc)"
    echo "cpu=$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//')"
    echo "mem_kib=$(awk '/^MemTotal/ {print $2}' /proc/meminfo)"
    if command -v nvidia-smi >/dev/null; then
        echo "nvidia_smi=$(nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.sm,clocks.max.sm \
            --format=csv,noheader 2>&1 | head -4 | tr '\n' ';')"
    else
        echo "nvidia_smi=none"
    fi
    echo "egl_vendor_files=$(ls /usr/share/glvnd/egl_vendor.d /etc/glvnd/egl_vendor.d 2>/dev/null | tr '\n' ' ')"
} >"$OUT/device.txt"
cat "$OUT/device.txt"

# The work, most important first: every scene at 256 (the issue's goal) in the paper's thin
# mode; Live's updates at 256 (issue 29: the bunny at 30 a second with hybrid); thin at 512,
# 128; the cpu's thread scaling on 16 cores; conservative at 256; the price of colour and
# normal voxels at 512 (issue 12); then 1024 and the rest of conservative. A run cut short
# keeps every row made so far.
ALL_SCENES=bunny_stanford_69k.ply.gz,dragon_stanford_res2_203k.ply.gz,sponza_crytek_262k_vcolor.ply.gz,triangle
ALL_SCENES=$ALL_SCENES,dragon_stanford_871k.ply.gz,dragon_stanford_871k.ply.gz:x4,dragon_stanford_871k.ply.gz:x16
if [ "${REHEARSAL:-0}" = 1 ]; then
    : "${ORDER:=thin@256,live@128,thin@128,threads@256,conservative@128,attributes@128}"
    : "${SCENES:=bunny_stanford_69k.ply.gz,dragon_stanford_res2_203k.ply.gz,sponza_crytek_262k_vcolor.ply.gz,triangle,dragon_stanford_871k.ply.gz,dragon_stanford_871k.ply.gz:x4}"
    : "${REPEAT:=2}" "${ROW_BUDGET_S:=1}" "${BUDGET_S:=200}" "${TIMEOUT_S:=280}"
else
    : "${ORDER:=thin@256,live@256,thin@512,thin@128,threads@512,conservative@256,attributes@512,thin@1024,conservative@512,conservative@128,conservative@1024}"
    : "${SCENES:=$ALL_SCENES}"
    : "${REPEAT:=5}" "${ROW_BUDGET_S:=2}" "${BUDGET_S:=300}" "${TIMEOUT_S:=345}"
    : "${REQUIRE_HARDWARE:=1}"  # a lent GPU: stop at once when GL is not on it
fi
HW=()
[ "${REQUIRE_HARDWARE:-0}" = 1 ] && HW=(--require-hardware)
echo "# ORDER=$ORDER"
echo "# SCENES=$SCENES"
echo "# REPEAT=$REPEAT ROW_BUDGET_S=$ROW_BUDGET_S BUDGET_S=$BUDGET_S TIMEOUT_S=$TIMEOUT_S"
start=$(date +%s)
timeout -k 10 "$TIMEOUT_S" "$HERE/bin/bench_device" --mesh-dir "$HERE/meshes" --csv "$OUT/table1.csv" \
    --info "$OUT/gl_info.txt" --order "$ORDER" --scenes "$SCENES" --repeat "$REPEAT" \
    --row-budget-s "$ROW_BUDGET_S" --budget-s "$BUDGET_S" "${HW[@]}"
rc=$?
if [ $rc = 3 ]; then  # no hardware GL context: what the next try needs to know
    echo "# diagnostics:"
    ls -la /dev/nvidia* /dev/dri 2>&1 | head -20
    ls /usr/local/nvidia /usr/local/nvidia/lib64 2>&1 | grep -i -E 'egl|glx|gl_|^/|:' | head -20
    find / -xdev -maxdepth 6 -name '*.json' -path '*vendor.d*' 2>/dev/null | head
    ldconfig -p | grep -i -E 'libEGL|libOpenGL|nvidia-egl|GLdispatch' | head -20
    env | grep -E '^(__EGL|__GLX|LD_LIBRARY|NVIDIA)' || true
fi
echo "# bench_device exit $rc after $(($(date +%s) - start)) s (124/137: stopped by the timeout; 1: a check failed)"
if [ ! -s "$OUT/table1.csv" ]; then
    echo "# no table1.csv"
elif command -v python3 >/dev/null && [ -e "$HERE/table.py" ]; then
    # The tables as results (results/*.json, *.md: copy them into bench/results/ of the checkout).
    python3 "$HERE/table.py" "$OUT/table1.csv" --info "$OUT/gl_info.txt" --device "$OUT/device.txt" \
        --out "$OUT/results" || true
    python3 "$HERE/table.py" "$OUT/table1.csv" --verify || true
else
    echo "# rows: $(($(wc -l <"$OUT/table1.csv") - 1)); failed checks:"
    grep -E ',(DIFF|ERROR[^,]*),' "$OUT/table1.csv" | cut -d, -f2,4,5,6,22-26
fi
finish "$rc"
