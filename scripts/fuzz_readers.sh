#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Fuzzes the strict mesh readers, the gzip input and voxelize() (tests/fuzz/: libFuzzer +
# ASan + UBSan, clang) for a fixed time each and fails on any finding: a crash, a sanitizer
# report, an exception other than InvalidInput, an out-of-range index, cpu voxels the
# reference does not explain, a 10 s input or 2 GiB of memory. A finding's input is left in
# build-fuzz/findings/<target>/; make it a regression case (readers:
# tests/native/test_io_mesh_strict.cpp) before fixing it.
#   FUZZ_SECONDS=600 bash scripts/fuzz_readers.sh   (default: 60 s per reader, 30 s for gzip
#                                                     and voxelize; FUZZ_SECONDS sets all)
set -euo pipefail
cd "$(dirname "$0")/.."
export PATH="/usr/bin:/bin:$PATH"
seconds=${FUZZ_SECONDS:-60}
meshes=${HYVOX_MESH_DIR:-../shared/data/meshes}

cmake -S tests/fuzz -B build-fuzz -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build-fuzz

for format in ply obj; do
  # A fresh corpus each run, seeded with the committed seeds and the small shared meshes
  # (the OBJ seed is the teapot, converted here).
  corpus=build-fuzz/corpus/$format
  findings=build-fuzz/findings/$format
  rm -rf "$corpus" "$findings"
  mkdir -p "$corpus" "$findings"
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
  echo "== fuzzing the $format reader for ${seconds} s"
  build-fuzz/fuzz_${format}_reader -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=65536 \
    -print_final_stats=1 -artifact_prefix="$findings/" "$corpus" 2>&1 | tail -n 12
  status=${PIPESTATUS[0]}
  if [ "$status" -ne 0 ] || [ -n "$(ls -A "$findings")" ]; then
    echo "fuzz_readers: the $format reader has a finding (exit $status): $findings" >&2
    exit 1
  fi
done
# The gzip input (with the PLY reader behind it), seeded with the PLY seeds compressed, and
# voxelize() on random small meshes, cpu against the reference (its own bytes, no seeds).
for target in gzip_input voxelize; do
  corpus=build-fuzz/corpus/$target
  findings=build-fuzz/findings/$target
  rm -rf "$corpus" "$findings"
  mkdir -p "$corpus" "$findings"
  if [ "$target" = gzip_input ]; then
    python3 - "$corpus" tests/fuzz/seeds/ply/* "$meshes/teapot_utah.ply" <<'PY'
import gzip, os, sys
for path in sys.argv[2:]:
    with open(path, "rb") as f, open(os.path.join(sys.argv[1], os.path.basename(path) + ".gz"), "wb") as out:
        out.write(gzip.compress(f.read()))
PY
  fi
  echo "== fuzzing $target for ${FUZZ_SECONDS:-30} s"
  build-fuzz/fuzz_$target -max_total_time="${FUZZ_SECONDS:-30}" -timeout=10 -rss_limit_mb=2048 -max_len=65536 \
    -print_final_stats=1 -artifact_prefix="$findings/" "$corpus" 2>&1 | tail -n 12
  status=${PIPESTATUS[0]}
  if [ "$status" -ne 0 ] || [ -n "$(ls -A "$findings")" ]; then
    echo "fuzz_readers: $target has a finding (exit $status): $findings" >&2
    exit 1
  fi
done
echo "fuzz_readers: no findings"
