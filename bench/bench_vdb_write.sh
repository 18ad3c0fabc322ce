#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Benchmark (not a test): the .vdb output of two CLI builds side by side (e.g. before/after a
# writer change). Runs `voxelize --method cpu` of MESH at RES alternately with each build,
# RUNS times, and prints the medians of the stats JSON's build_vdb and write_vdb (ms) and the
# file's size (bytes).
# The table also goes to DIR/vdb_write.{json,md} (OUT=DIR, default bench/results/).
#   bench/bench_vdb_write.sh BASE_BUILD NEW_BUILD MESH RES [RUNS=5]
set -euo pipefail
base=$1 new=$2 mesh=$3 res=$4 runs=${5:-5}
here=$(cd "$(dirname "$0")" && pwd)
out=${OUT:-$here/results}
command="bench/bench_vdb_write.sh $*"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for _ in $(seq "$runs"); do
  for name in base new; do
    build=$base
    [ "$name" = new ] && build=$new
    "$build/hyvox" voxelize "$mesh" -o "$work/$name.vdb" --resolution "$res" --method cpu \
      --stats-json "$work/$name.json" > /dev/null
    /usr/bin/python3 -c "import json, os, sys; t = json.load(open(sys.argv[2]))['timings_ms']; \
print(sys.argv[1], t['build_vdb'], t['write_vdb'], os.path.getsize(sys.argv[3]))" \
      "$name" "$work/$name.json" "$work/$name.vdb"
  done
done | /usr/bin/python3 -c "
import statistics, sys
sys.path.insert(0, sys.argv[1])
from bench_results import Column, Table
table = Table('vdb_write', 'The .vdb output of two builds', [Column('build'), Column('build_vdb ms', 1),
              Column('write_vdb ms', 1), Column('sum ms', 1), Column('bytes'), Column('runs')], command=sys.argv[3])
rows = {}
for line in sys.stdin:
    name, build, write, size = line.split()
    rows.setdefault(name, []).append((float(build), float(write), int(size)))
for name, r in rows.items():
    print(f'{name}: build_vdb {statistics.median(x[0] for x in r):.1f} ms, write_vdb {statistics.median(x[1] for x in r):.1f} ms, '
          f'sum {statistics.median(x[0] + x[1] for x in r):.1f} ms, {r[0][2]} bytes ({len(r)} runs)')
    table.add([name, statistics.median(x[0] for x in r), statistics.median(x[1] for x in r),
               statistics.median(x[0] + x[1] for x in r), r[0][2], len(r)])
table.note('Medians of the stats JSON timings, the two builds alternating; base: ' + sys.argv[4] +
           ', new: ' + sys.argv[5] + '.')
table.write(sys.argv[2])
" "$here" "$out" "$command" "$base" "$new"
