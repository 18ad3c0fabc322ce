#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Prints the path of a Python X.Y on this machine, for the release's builds and tests of
# the Python that /usr/bin/python3 is not (3.13 on Debian 12, 3.11 on Debian 13):
#   scripts/find_python.sh 3.13
# Looked for in order: $HYVOX_PYTHON_XY (e.g. HYVOX_PYTHON_313), /usr/bin/pythonX.Y, pythonX.Y
# on PATH, and pyenv's versions (pyenv's shim answers only for the versions pyenv has
# selected, so its folders are read directly). Fails with a line naming what was tried.
set -euo pipefail
if [ $# -ne 1 ] || ! [[ "$1" =~ ^3\.[0-9]+$ ]]; then
  echo "usage: $0 X.Y" >&2
  exit 2
fi
version=$1
override_name="HYVOX_PYTHON_${version/./}"
candidates=("${!override_name:-}" "/usr/bin/python$version" "$(command -v "python$version" 2>/dev/null || true)")
pyenv_root=$(pyenv root 2>/dev/null || echo "${PYENV_ROOT:-$HOME/.pyenv}")
for found in "$pyenv_root"/versions/"$version"*/bin/"python$version"; do candidates+=("$found"); done
for python in "${candidates[@]}"; do
  [ -n "$python" ] && [ -x "$python" ] || continue
  if [ "$("$python" -c 'import sys; print("%d.%d" % sys.version_info[:2])' 2>/dev/null)" = "$version" ]; then
    echo "$python"
    exit 0
  fi
done
echo "find_python: no Python $version here (tried \$$override_name, /usr/bin/python$version," \
     "python$version on PATH, $pyenv_root/versions/$version*)" >&2
exit 1
