#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Checks that the sweeps (ctest label `sweep`, tests/native/CMakeLists.txt) reach no line of
# native/src that the other native tests do not reach: the sanitizer build runs only those
# others. A gcov build of the native tests runs them without the sweeps, then the sweeps alone,
# and lists the lines only the sweeps reach; any such line fails (not part of the test command:
# a third build, run when the sweeps or their meshes change).
#   bash scripts/sweep_coverage.sh [BUILD]      (default build-coverage/)
set -euo pipefail
cd "$(dirname "$0")/.."
export PATH="/usr/bin:/bin:$PATH"
build=${1:-build-coverage}
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=MinSizeRel -DCMAKE_CXX_FLAGS=--coverage \
  -DCMAKE_C_FLAGS=--coverage -DCMAKE_EXE_LINKER_FLAGS=--coverage -DCMAKE_SHARED_LINKER_FLAGS=--coverage \
  -DCMAKE_MODULE_LINKER_FLAGS=--coverage -DHYVOX_BUILD_PYTHON=OFF -DHYVOX_BUILD_BENCH=OFF \
  -DHYVOX_API_DOC_TEST=OFF >/dev/null
cmake --build "$build" -j "$(nproc)"
# lines NAME: runs nothing; writes the lines of native/src the last run reached to BUILD/NAME.lines.
lines() {
  /usr/bin/python3 - "$build" "$PWD/native/src/" >"$build/$1.lines" <<'PY'
import glob, gzip, json, os, subprocess, sys, tempfile
build, root = sys.argv[1], sys.argv[2]
hit = set()
with tempfile.TemporaryDirectory() as tmp:
    for gcda in glob.glob(os.path.join(build, "native", "**", "*.gcda"), recursive=True):
        subprocess.run(["gcov", "-j", "-o", os.path.dirname(os.path.abspath(gcda)), os.path.abspath(gcda)],
                       cwd=tmp, capture_output=True, check=False)
    for path in glob.glob(os.path.join(tmp, "*.gcov.json.gz")):
        data = json.load(gzip.open(path))
        for file in data["files"]:
            name = os.path.realpath(os.path.join(data.get("current_working_directory", ""), file["file"]))
            if name.startswith(root):
                hit.update(f"{name[len(root):]}:{line['line_number']}" for line in file["lines"] if line["count"])
print("\n".join(sorted(hit)))
PY
}
find "$build" -name '*.gcda' -delete
ctest --test-dir "$build" -j "$(nproc)" -LE 'sweep|layering' >"$build/others.log" || { tail -20 "$build/others.log"; exit 1; }
lines others
find "$build" -name '*.gcda' -delete
ctest --test-dir "$build" -j "$(nproc)" -L sweep >"$build/sweeps.log" || { tail -20 "$build/sweeps.log"; exit 1; }
lines sweeps
only=$(comm -13 "$build/others.lines" "$build/sweeps.lines")
echo "sweep_coverage: the sweeps reach $(wc -l <"$build/sweeps.lines") lines of native/src, the other tests $(wc -l <"$build/others.lines")"
if [ -n "$only" ]; then
  echo "sweep_coverage: lines only the sweeps reach (give one of the sanitized meshes a case that does):" >&2
  echo "$only" >&2
  exit 1
fi
echo "sweep_coverage: every line the sweeps reach, the other tests reach"
