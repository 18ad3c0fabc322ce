#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Copies the licence texts that scripts/release/licences.txt names into OUT, one NAME.txt
# each, from the pinned sources in SOURCES and zig's own files under ZIG_LIB_ROOT:
#   scripts/release/collect_licences.sh SOURCES ZIG_LIB_ROOT OUT
# A text that is missing fails the release.
set -euo pipefail
if [ $# -ne 3 ]; then
  echo "usage: $0 SOURCES ZIG_LIB_ROOT OUT" >&2
  exit 2
fi
here=$(cd "$(dirname "$0")" && pwd)
sources=$1 zig_root=$2 out=$3
mkdir -p "$out"
while read -r name package path; do
  target="$out/$name.txt"
  if [ "$package" = zig ]; then
    cp "$zig_root/$path" "$target"
    continue
  fi
  file=$(awk -v p="$package" '$1 == p { print $3 }' "$here/sources.txt")
  case "$file" in
    *.deb) dpkg-deb --fsys-tarfile "$sources/$file" | tar -xO --wildcards --no-wildcards-match-slash "$path" > "$target" ;;
    *) tar -xOf "$sources/$file" --wildcards --no-wildcards-match-slash "$path" > "$target" ;;
  esac
  if [ ! -s "$target" ]; then
    echo "collect_licences: no $path in $file" >&2
    exit 1
  fi
done < <(grep -v '^#' "$here/licences.txt" | grep -v '^[[:space:]]*$')
