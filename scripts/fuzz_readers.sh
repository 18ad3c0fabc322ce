#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Fuzzes the strict mesh readers (PLY, OBJ, STL, OFF, glTF), the formats read through assimp (in
# the assimp reader process, as readMesh reads them), the gzip input, voxelize(), solid mode
# with attributes and the sdf's band distances (tests/fuzz/: libFuzzer + ASan + UBSan, clang)
# for a fixed time each
# and fails on any finding: a crash, a sanitizer report, an exception other than
# InvalidInput, an out-of-range index, cpu voxels the reference does not explain, solid
# voxels or attribute values against their oracle (tests/fuzz/fuzz_solid.cpp), band distances
# against a brute-force closest point (tests/fuzz/fuzz_sdf.cpp), a 10 s input
# or 2 GiB of memory. A finding's input is left in BUILD/fuzz/findings/<target>/; make it a
# regression case (readers: tests/native/test_io_mesh_strict.cpp, test_io_mesh_formats.cpp,
# tests/regressions/meshes/) before fixing it.
# The targets run one per core at a time, from the fuzzing build BUILD (default build-sanitize,
# made by `bash scripts/test_all.sh sanitize`):
#   FUZZ_SECONDS=600 bash scripts/fuzz_readers.sh [BUILD]   (default: 60 s for PLY and OBJ, 20 s for
#                                                     STL, OFF, glTF and the FBX check, 30 s for
#                                                     the assimp formats,
#                                                     gzip, voxelize and sdf, 45 s for
#                                                     solid;
#                                                     FUZZ_SECONDS sets all)
#   FUZZ_TARGETS="stl_reader off_reader" ...        (only these)
set -euo pipefail
cd "$(dirname "$0")/.."
export PATH="/usr/bin:/bin:$PATH"
seconds=${FUZZ_SECONDS:-60}
meshes=${HYVOX_MESH_DIR:-../shared/data/meshes}

build=${1:-build-sanitize}
if [ ! -f "$build/build.ninja" ] || ! grep -q 'HYVOX_FUZZ:BOOL=ON' "$build/CMakeCache.txt"; then
  echo "fuzz_readers: $build is not a fuzzing build: make it with bash scripts/test_all.sh sanitize" >&2
  exit 1
fi
targets=${FUZZ_TARGETS:-ply_reader obj_reader stl_reader off_reader gltf_reader fbx_check assimp_formats gzip_input voxelize solid sdf}
wanted() { [[ " $targets " == *" $1 "* ]]; }
# shellcheck disable=SC2046
cmake --build "$build" --target $(for t in $targets; do echo "fuzz_$t"; done)
work=$build/fuzz  # corpora and findings

# fresh TARGET: an empty corpus and findings folder for TARGET ($work/{corpus,findings}/TARGET).
fresh() {
  rm -rf "$work/corpus/$1" "$work/findings/$1"
  mkdir -p "$work/corpus/$1" "$work/findings/$1"
}
# fuzz TARGET SECONDS: runs $build/fuzz_TARGET on its corpus; fails on any finding.
fuzz() {
  local findings=$work/findings/$1
  echo "== fuzzing $1 for $2 s"
  # `|| status=`: under set -e and pipefail a crashing fuzzer would otherwise end the function
  # here, before it names the findings folder.
  local status=0
  "$build/fuzz_$1" -max_total_time="$2" -timeout=10 -rss_limit_mb=2048 -max_len=65536 \
    -print_final_stats=1 -artifact_prefix="$findings/" "$work/corpus/$1" 2>&1 | tail -n 12 ||
    status=${PIPESTATUS[0]}
  if [ "$status" -ne 0 ] || [ -n "$(ls -A "$findings")" ]; then
    echo "fuzz_readers: $1 has a finding (exit $status): $findings" >&2
    return 1
  fi
}
# queue TARGET SECONDS: fuzzes TARGET once every corpus is ready (run_queue).
queued=()
queue() { queued+=("$1 $2"); }
# run_queue: the queued fuzzers, one per core at a time (each is single-threaded), each one's
# output shown whole when it ends; fails after all have run if any found something.
run_queue() {
  local parallel pids=() names=() failed=0 i
  parallel=$(nproc)
  for item in "${queued[@]}"; do
    while [ "$(jobs -rp | wc -l)" -ge "$parallel" ]; do wait -n || true; done
    read -r name secs <<<"$item"
    (fuzz "$name" "$secs" >"$work/$name.log" 2>&1) &
    pids+=($!)
    names+=("$name")
  done
  for i in "${!pids[@]}"; do
    wait "${pids[$i]}" || failed=1
    cat "$work/${names[$i]}.log"
  done
  return $failed
}

for format in ply obj; do
  wanted "${format}_reader" || continue
  # A fresh corpus each run, seeded with the committed seeds and the small shared meshes
  # (the OBJ seed is the teapot, converted here).
  corpus=$work/corpus/${format}_reader
  fresh "${format}_reader"
  cp tests/fuzz/seeds/$format/* "$corpus/"
  if [ "$format" = ply ]; then
    cp "$meshes/spider_messy.ply" "$meshes/teapot_utah.ply" "$corpus/"
  else
    python3 - "$meshes/teapot_utah.ply" "$corpus/teapot.obj" <<'PY'
import sys
data = open(sys.argv[1], "rb").read()
body = data.index(b"end_header\n") + len(b"end_header\n")
import numpy as np
lines = data[:body].decode().splitlines()
nv = int(next(l for l in lines if l.startswith("element vertex")).split()[2])
nf = int(next(l for l in lines if l.startswith("element face")).split()[2])
v = np.frombuffer(data, "<f4", 3 * nv, body).reshape(-1, 3)
f = np.frombuffer(data, np.dtype([("n", "u1"), ("i", "<i4", 3)]), nf, body + v.nbytes)["i"]
with open(sys.argv[2], "w") as out:
    out.writelines(f"v {x:.6g} {y:.6g} {z:.6g}\n" for x, y, z in v)
    out.writelines(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in f)
PY
  fi
  queue "${format}_reader" "$seconds"
done
# STL, OFF, glTF and the formats read through assimp: the committed seeds (hand-made variants
# and decided findings) and the small shared meshes written in each format
# (tests/fuzz/format_seeds.py).
for target in stl_reader off_reader gltf_reader fbx_check assimp_formats; do
  wanted "$target" || continue
  fresh "$target"
  seeds=${target%_reader}
  cp tests/fuzz/seeds/"${seeds%_check}"/* "$work/corpus/$target/"
  python3 tests/fuzz/format_seeds.py "$target" "$work/corpus/$target" "$meshes/spider_messy.ply" \
    "$meshes/teapot_utah.ply"
  default_seconds=20
  if [ "$target" = assimp_formats ]; then default_seconds=30; fi
  queue "$target" "${FUZZ_SECONDS:-$default_seconds}"
done
# The gzip input (with the PLY reader behind it), seeded with the PLY seeds compressed,
# voxelize() on random small meshes, cpu against the reference, solid mode with attributes
# against a brute-force winding number, and the sdf's band distances against a brute-force
# closest point (their own bytes, seeded with hand-made shapes and the decided findings).
for target in gzip_input voxelize solid sdf; do
  wanted "$target" || continue
  fresh "$target"
  if [ "$target" = gzip_input ]; then
    python3 - "$work/corpus/$target" tests/fuzz/seeds/ply/* "$meshes/teapot_utah.ply" <<'PY'
import gzip, os, sys
for path in sys.argv[2:]:
    with open(path, "rb") as f, open(os.path.join(sys.argv[1], os.path.basename(path) + ".gz"), "wb") as out:
        out.write(gzip.compress(f.read()))
PY
  fi
  # Decided findings replay first (tests/fuzz/findings/README.md).
  if [ -d "tests/fuzz/seeds/$target" ]; then cp "tests/fuzz/seeds/$target"/* "$work/corpus/$target/"; fi
  default_seconds=30
  if [ "$target" = solid ]; then default_seconds=45; fi
  queue "$target" "${FUZZ_SECONDS:-$default_seconds}"
done
run_queue || { echo "fuzz_readers: findings above" >&2; exit 1; }
echo "fuzz_readers: no findings"
