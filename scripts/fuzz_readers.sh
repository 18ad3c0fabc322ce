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
# or 2 GiB of memory. A finding's input is left in build-fuzz/findings/<target>/; make it a
# regression case (readers: tests/native/test_io_mesh_strict.cpp, test_io_mesh_formats.cpp,
# tests/regressions/meshes/) before fixing it.
#   FUZZ_SECONDS=600 bash scripts/fuzz_readers.sh   (default: 60 s for PLY and OBJ, 20 s for
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

cmake -S tests/fuzz -B build-fuzz -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build-fuzz
targets=${FUZZ_TARGETS:-ply_reader obj_reader stl_reader off_reader gltf_reader fbx_check assimp_formats gzip_input voxelize solid sdf}
wanted() { [[ " $targets " == *" $1 "* ]]; }

# fresh TARGET: an empty corpus and findings folder for TARGET (build-fuzz/{corpus,findings}/TARGET).
fresh() {
  rm -rf "build-fuzz/corpus/$1" "build-fuzz/findings/$1"
  mkdir -p "build-fuzz/corpus/$1" "build-fuzz/findings/$1"
}
# fuzz TARGET SECONDS: runs build-fuzz/fuzz_TARGET on its corpus; exits 1 on any finding.
fuzz() {
  local findings=build-fuzz/findings/$1
  echo "== fuzzing $1 for $2 s"
  # `|| status=`: under set -e and pipefail a crashing fuzzer would otherwise end the script
  # here, before it names the findings folder.
  local status=0
  "build-fuzz/fuzz_$1" -max_total_time="$2" -timeout=10 -rss_limit_mb=2048 -max_len=65536 \
    -print_final_stats=1 -artifact_prefix="$findings/" "build-fuzz/corpus/$1" 2>&1 | tail -n 12 ||
    status=${PIPESTATUS[0]}
  if [ "$status" -ne 0 ] || [ -n "$(ls -A "$findings")" ]; then
    echo "fuzz_readers: $1 has a finding (exit $status): $findings" >&2
    exit 1
  fi
}

for format in ply obj; do
  wanted "${format}_reader" || continue
  # A fresh corpus each run, seeded with the committed seeds and the small shared meshes
  # (the OBJ seed is the teapot, converted here).
  corpus=build-fuzz/corpus/${format}_reader
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
  fuzz "${format}_reader" "$seconds"
done
# STL, OFF, glTF and the formats read through assimp: the committed seeds (hand-made variants
# and decided findings) and the small shared meshes written in each format
# (tests/fuzz/format_seeds.py).
for target in stl_reader off_reader gltf_reader fbx_check assimp_formats; do
  wanted "$target" || continue
  fresh "$target"
  seeds=${target%_reader}
  cp tests/fuzz/seeds/"${seeds%_check}"/* "build-fuzz/corpus/$target/"
  python3 tests/fuzz/format_seeds.py "$target" "build-fuzz/corpus/$target" "$meshes/spider_messy.ply" \
    "$meshes/teapot_utah.ply"
  default_seconds=20
  if [ "$target" = assimp_formats ]; then default_seconds=30; fi
  fuzz "$target" "${FUZZ_SECONDS:-$default_seconds}"
done
# The gzip input (with the PLY reader behind it), seeded with the PLY seeds compressed,
# voxelize() on random small meshes, cpu against the reference, solid mode with attributes
# against a brute-force winding number, and the sdf's band distances against a brute-force
# closest point (their own bytes, seeded with hand-made shapes and the decided findings).
for target in gzip_input voxelize solid sdf; do
  wanted "$target" || continue
  fresh "$target"
  if [ "$target" = gzip_input ]; then
    python3 - "build-fuzz/corpus/$target" tests/fuzz/seeds/ply/* "$meshes/teapot_utah.ply" <<'PY'
import gzip, os, sys
for path in sys.argv[2:]:
    with open(path, "rb") as f, open(os.path.join(sys.argv[1], os.path.basename(path) + ".gz"), "wb") as out:
        out.write(gzip.compress(f.read()))
PY
  fi
  # Decided findings replay first (tests/fuzz/findings/README.md).
  if [ -d "tests/fuzz/seeds/$target" ]; then cp "tests/fuzz/seeds/$target"/* "build-fuzz/corpus/$target/"; fi
  default_seconds=30
  if [ "$target" = solid ]; then default_seconds=45; fi
  fuzz "$target" "${FUZZ_SECONDS:-$default_seconds}"
done
echo "fuzz_readers: no findings"
