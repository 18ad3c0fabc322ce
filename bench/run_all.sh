#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Runs the benchmarks docs/benchmarks.md shows, one after the other, each writing its table to
# OUT/NAME.json and .md, then rebuilds the page from them (bench/make_benchmarks_page.py).
#   bash bench/run_all.sh [--quick] [--build DIR] [--out DIR]
# --build: a Release build with the benchmarks (default build/); --out: where the results go
# (default bench/results/, and then docs/benchmarks.md is rebuilt; another folder gets its own
# benchmarks.md). --quick runs every benchmark at small sizes, to check that they all work (its
# results say so). Optional parts: PEER=/path/to/cuda_voxelizer adds the comparison with
# cuda_voxelizer's CPU path; a bench/.venv with libigl (bench/requirements-py311.txt) adds the
# three-way solid comparison; Blender 5.0's bpy module (BPY50=python, default
# BUILD/venv/bpy50/bin/python from scripts/setup_venvs.sh) adds Live's. Run it on an idle
# machine: every figure is wall time. Nothing is stopped by a failing benchmark; the status is 1
# when any failed, and they are listed.
set -uo pipefail
cd "$(dirname "$0")/.."
BUILD=build OUT= QUICK=0
while [ $# -gt 0 ]; do
  case $1 in
    --quick) QUICK=1 ;;
    --build) BUILD=${2:?--build needs a folder}; shift ;;
    --out) OUT=${2:?--out needs a folder}; shift ;;
    -h|--help) sed -n '3,14p' "$0" | cut -c3-; exit 0 ;;
    *) echo "run_all.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
  shift
done
# Paths stay as typed, relative to the checkout, so that the results' commands read the same
# on every machine.
[ -d "$BUILD" ] || { echo "run_all.sh: no build folder $BUILD" >&2; exit 2; }
for needed in hyvox bench/bench_mesh_to_volume bench/bench_solid bench/bench_tessellation bench/bench_gl_hybrid \
    bench/bench_mesh_read bench/bench_sdf python/hyvox; do
  [ -e "$BUILD/$needed" ] || { echo "run_all.sh: $BUILD/$needed is missing: build the project first" >&2; exit 2; }
done
PAGE_ARGS=()
if [ -z "$OUT" ]; then
  OUT=bench/results
else
  mkdir -p "$OUT" || exit 2
  PAGE_ARGS=(--results "$OUT" --page "$OUT/benchmarks.md")
fi
export PATH=/usr/bin:/bin:$PATH PYTHONPATH=$BUILD/python
[ "$QUICK" = 1 ] && export HYVOX_BENCH_QUICK=1
M=../shared/data/meshes
PY=/usr/bin/python3
BPY50=${BPY50:-$BUILD/venv/bpy50/bin/python}
failed=()

# run NAME COMMAND...: one benchmark, timed, its failure noted.
run() {
  local name=$1 start=$SECONDS
  shift
  echo "== $name: $*"
  if "$@"; then
    echo "== $name: $((SECONDS - start)) s"
  else
    echo "== $name FAILED (status $?) after $((SECONDS - start)) s"
    failed+=("$name")
  fi
}

B=$BUILD/bench
MESHES_4=bunny_stanford_69k.ply,dragon_stanford_res2_203k.ply.gz,dragon_stanford_871k.ply.gz
MESHES_4=$MESHES_4,sponza_crytek_262k_vcolor.ply.gz
if [ "$QUICK" = 1 ]; then
  run mesh_to_volume "$B/bench_mesh_to_volume" --runs 1 --res 64 --out "$OUT" bunny_stanford_69k.ply
  run solid "$B/bench_solid" --runs 1 --res 64 --out "$OUT" happy_buddha_100k.ply sponza_crytek_262k_vcolor.ply.gz
  run sdf "$B/bench_sdf" --runs 1 --res 64 --out "$OUT" spot_vcolor.ply bunny_stanford_69k.ply
  run sparse_scale $PY bench/bench_sparse_scale.py --build "$BUILD" --res 128,256 --out "$OUT" \
    "$M/bunny_stanford_69k.ply"
  run memory_estimate $PY bench/bench_memory_estimate.py --cli "$BUILD/hyvox" --resolutions 256 --only spot,bunny \
    --out "$OUT"
  run attributes $PY bench/bench_attributes.py --resolutions 64 --repeats 1 --out "$OUT"
  run attributes_solid $PY bench/bench_attributes.py --resolutions 64 --repeats 1 --mode solid --out "$OUT"
  run tessellation "$B/bench_tessellation" --res 64 --repeat 1 --gammas 2 --out "$OUT" \
    "$M/bunny_stanford_69k.ply" "$M/spot_vcolor.ply"
  run tessellation_seal_sweep $PY bench/tessellation_seal_sweep.py --shapes 2 --gammas 1,2 --out "$OUT"
  run gl_hybrid "$B/bench_gl_hybrid" --res 64 --repeat 1 --out "$OUT" bunny_stanford_69k.ply triangle
  run blender_addon blender -b --factory-startup -noaudio --python bench/bench_blender_addon.py -- \
    --build "$BUILD" --levels 2 --resolutions 64 --repeat 1 --out "$OUT"
  run mesh_read "$B/bench_mesh_read" --repeat 1 --out "$OUT" "$M/bunny_stanford_69k.ply"
  run regions $PY bench/bench_regions.py --build "$BUILD" --res 512 --regions 4 --out "$OUT"
  [ -x "$BUILD/venv/farm/bin/openjd" ] && run farm $PY bench/bench_farm.py --build "$BUILD" --frames 4 \
    --resolution 32 --chunks 1,2 --out "$OUT"
  [ -x "$BPY50" ] && run live "$BPY50" bench/bench_live.py --build "$BUILD" --meshes bunny --resolutions 64 \
    --edits 2 --animation-frames 4 --out "$OUT"
  [ -n "${PEER:-}" ] && run vs_cuda_voxelizer $PY bench/bench_vs_cuda_voxelizer.py --peer "$PEER" \
    --build "$BUILD" --meshes bunny_stanford_69k.ply --res 64 --runs 1 --out "$OUT"
  [ -x bench/.venv/bin/python ] && run solid_three_way bench/.venv/bin/python bench/bench_solid_three_way.py \
    --bench-solid "$B/bench_solid" --res 32 --samples 5 --out "$OUT" happy_buddha_100k.ply
else
  run mesh_to_volume "$B/bench_mesh_to_volume" --out "$OUT"
  run solid "$B/bench_solid" --runs 1 --out "$OUT"
  run sdf "$B/bench_sdf" --out "$OUT"
  run sparse_scale $PY bench/bench_sparse_scale.py --build "$BUILD" --res 1024,2048,4096,8192 --out "$OUT" \
    "$M/dragon_stanford_871k.ply.gz" "$M/sponza_crytek_262k_vcolor.ply.gz"
  run memory_estimate $PY bench/bench_memory_estimate.py --cli "$BUILD/hyvox" --out "$OUT"
  run attributes $PY bench/bench_attributes.py --resolutions 256,512 --repeats 3 --out "$OUT"
  run attributes_solid $PY bench/bench_attributes.py --resolutions 256,512 --repeats 3 --mode solid --out "$OUT"
  run tessellation "$B/bench_tessellation" --res 256 --repeat 2 --gammas 1,2,4 --out "$OUT" \
    "$M/bunny_stanford_69k.ply" "$M/happy_buddha_100k.ply" "$M/dragon_stanford_res2_203k.ply.gz" \
    "$M/dragon_stanford_871k.ply.gz" "$M/armadillo_52k.ply" "$M/igea_cyberware_268k.ply.gz" "$M/spot_vcolor.ply"
  run tessellation_seal_sweep $PY bench/tessellation_seal_sweep.py --shapes 16 --seed 99 --out "$OUT"
  run gl_hybrid "$B/bench_gl_hybrid" --repeat 3 --out "$OUT"
  run blender_addon blender -b --factory-startup -noaudio --python bench/bench_blender_addon.py -- \
    --build "$BUILD" --levels 4,5 --resolutions 256,512 --repeat 3 --out "$OUT"
  run mesh_read "$B/bench_mesh_read" --repeat 7 --out "$OUT" "$M/bunny_stanford_69k.ply" \
    "$M/dragon_stanford_871k.ply.gz" "$M/sponza_crytek_262k_vcolor.ply.gz"
  run regions $PY bench/bench_regions.py --build "$BUILD" --out "$OUT"
  [ -x "$BUILD/venv/farm/bin/openjd" ] && run farm $PY bench/bench_farm.py --build "$BUILD" --out "$OUT"
  [ -x "$BPY50" ] && run live "$BPY50" bench/bench_live.py --build "$BUILD" --out "$OUT"
  [ -n "${PEER:-}" ] && run vs_cuda_voxelizer $PY bench/bench_vs_cuda_voxelizer.py --peer "$PEER" \
    --build "$BUILD" \
    --meshes "$MESHES_4" \
    --res 128,256,512,1024 --runs 6 --out "$OUT"
  [ -x bench/.venv/bin/python ] && run solid_three_way bench/.venv/bin/python bench/bench_solid_three_way.py \
    --bench-solid "$B/bench_solid" --res 128,256 --samples 100 --out "$OUT"
fi

run page $PY bench/make_benchmarks_page.py "${PAGE_ARGS[@]}"
if [ ${#failed[@]} -gt 0 ]; then
  echo "run_all.sh: failed: ${failed[*]}"
  exit 1
fi
echo "run_all.sh: all ran in $SECONDS s; results in $OUT"
