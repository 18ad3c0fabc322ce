#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The project's linters, in check mode over the tree; any finding fails:
#   ruff     ruff check and ruff format --check: the Python (ruff.toml)
#   format   clang-format --dry-run: the C++'s format (.clang-format)
#   tidy     clang-tidy: every C++ source of BUILD/compile_commands.json (.clang-tidy), headers
#            with them (needs a configured BUILD and its generated build id header)
# To format what a check refuses: build/venv/lint/bin/ruff format . and
# build/venv/lint/bin/clang-format -i FILE...
#
#   scripts/lint.sh [BUILD [CHECK...]]   BUILD: a build folder (default build); CHECK: ruff,
#                                        format, tidy (default all three). The tools come pinned
#                                        (scripts/requirements/pyXY/lint.txt) in BUILD/venv/lint,
#                                        made on first use by scripts/setup_venvs.sh
# HYVOX_LINT_VENV_DIR=DIR takes the venvs from DIR instead of BUILD/venv.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
checks=("${@:2}")
[ ${#checks[@]} -gt 0 ] || checks=(ruff format tidy)
for check in "${checks[@]}"; do
  case "$check" in ruff|format|tidy) ;; *) echo "lint: no check '$check' (ruff, format, tidy)" >&2; exit 2 ;; esac
done
wanted() { [[ " ${checks[*]} " == *" $1 "* ]]; }
venvs=${HYVOX_LINT_VENV_DIR:-$build/venv}
bash scripts/setup_venvs.sh "$venvs" lint >/dev/null
bin="$venvs/lint/bin"
status=0
step() {  # step NAME COMMAND...: runs it, notes a failure, goes on
  echo "== lint: $1"
  "${@:2}" || { echo "lint: $1 found something (above)" >&2; status=1; }
}

if wanted ruff; then
  step "ruff check" "$bin/ruff" check --no-cache .
  step "ruff format --check" "$bin/ruff" format --check --no-cache .
fi

if wanted format; then
  mapfile -t cxx < <(git ls-files '*.cpp' '*.h')
  step "clang-format (${#cxx[@]} files)" "$bin/clang-format" --dry-run --Werror "${cxx[@]}"
fi

if wanted tidy; then
  if [ ! -f "$build/compile_commands.json" ]; then
    echo "lint: $build/compile_commands.json is missing: configure $build first (cmake -S . -B $build)" >&2
    exit 1
  fi
  # The project's own sources, not what the build generates, nor the programs of
  # tests/native/layering/, which must not compile.
  mapfile -t sources < <(/usr/bin/python3 - "$build" <<'PY'
import json, os, sys
root = os.getcwd() + os.sep
build = os.path.realpath(sys.argv[1]) + os.sep
for file in sorted({c["file"] for c in json.load(open(os.path.join(sys.argv[1], "compile_commands.json")))}):
    path = os.path.realpath(file)
    layering = os.path.join(root, "tests", "native", "layering") + os.sep
    if path.startswith(root) and not path.startswith((build, layering)) and path.endswith(".cpp"):
        print(os.path.relpath(path))
PY
  )
  tidy() { printf '%s\n' "${sources[@]}" | xargs -P "$(nproc)" -n 4 "$bin/clang-tidy" -p "$build" --quiet; }
  step "clang-tidy (${#sources[@]} sources)" tidy
fi
exit $status
