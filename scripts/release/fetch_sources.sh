#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Downloads the upstream tarballs (and one header-only .deb) of scripts/release/sources.txt into DIR and checks each
# against its sha256; a tarball already there and whole is kept.
#   scripts/release/fetch_sources.sh DIR
# The tarballs come from the Debian mirror this machine is configured with, through
# `apt-get source --print-uris` for bookworm's source packages: when bookworm's deb-src
# index is missing (Debian 13, or a machine with binary lines only) a deb-src line for it
# is added, on the same mirror, in /etc/apt/sources.list.d/hyvox-bookworm-src.sources.
set -euo pipefail
if [ $# -ne 1 ]; then
  echo "usage: $0 DIR" >&2
  exit 2
fi
here=$(cd "$(dirname "$0")" && pwd)
dest=$1
mkdir -p "$dest"
SUDO=""
[ "$(id -u)" -ne 0 ] && SUDO="sudo"

pinned() { grep -v '^#' "$here/sources.txt" | grep -v '^[[:space:]]*$'; }

# bookworm's source index, added at most once, before the first download.
index_checked=0
ensure_index() {
  [ $index_checked = 1 ] && return
  index_checked=1
  read -r probe_package probe_version _ < <(pinned)
  apt-cache showsrc "$probe_package" 2>/dev/null | grep -qx "Version: $probe_version" && return
  local mirror
  mirror=$(cat /etc/apt/sources.list /etc/apt/sources.list.d/*.list /etc/apt/sources.list.d/*.sources 2>/dev/null |
           grep -oE '^(URIs:|deb) +https?://[^ ]+/debian/?( |$)' | grep -m1 -oE 'https?://[^ ]+' || true)
  mirror=${mirror:-http://deb.debian.org/debian}
  echo "fetch_sources: adding bookworm's deb-src index from $mirror"
  printf 'Types: deb-src\nURIs: %s\nSuites: bookworm\nComponents: main\nSigned-By: /usr/share/keyrings/debian-archive-keyring.gpg\n' \
    "$mirror" | $SUDO tee /etc/apt/sources.list.d/hyvox-bookworm-src.sources >/dev/null
  $SUDO apt-get update -qq
}

while read -r package version file sha; do
  if echo "$sha  $dest/$file" | sha256sum -c --status 2>/dev/null; then
    continue
  fi
  ensure_index
  # The listed addresses are percent-encoded ('+' as %2b, '~' as %7e): compare them decoded.
  case "$file" in
    *.deb) listing=(apt-get download --print-uris) ;;   # a binary package
    *) listing=(apt-get source --print-uris) ;;
  esac
  url=$("${listing[@]}" "$package=$version" 2>/dev/null | cut -s -d"'" -f2 |
        while read -r candidate; do
          [ "$(basename "$(printf '%b' "${candidate//%/\\x}")")" = "$file" ] && echo "$candidate"
        done | head -1 || true)
  if [ -z "$url" ]; then
    echo "fetch_sources: ${listing[*]} $package=$version does not list $file" >&2
    exit 1
  fi
  echo "fetch_sources: $file"
  curl -fsSL --retry 3 -o "$dest/$file.part" "$url"
  if ! echo "$sha  $dest/$file.part" | sha256sum -c --status; then
    echo "fetch_sources: $file from $url does not have the pinned sha256 $sha" >&2
    rm -f "$dest/$file.part"
    exit 1
  fi
  mv "$dest/$file.part" "$dest/$file"
done < <(pinned)
