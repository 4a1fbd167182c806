#!/usr/bin/env bash
# A clone of the repository is all a user has: nothing in it may point at a folder beside it,
# the project's licence and citation are there, and every folder of inputs made by others
# names its source and carries its licence.
#
#   self_contained.sh SOURCE_DIR VERSION               # exit 1 naming each fault
#   self_contained.sh --self-test SOURCE_DIR VERSION   # also: a planted fault is caught
set -euo pipefail

# Built from pieces, so that this script does not find itself.
beside='\.\./'"shared"

# shellcheck source=files_of.sh
source "$(dirname "$0")/files_of.sh"

check() {
  local root=$1 version=$2 bad=0 f
  while IFS= read -r f; do
    [ -f "$root/$f" ] || continue
    if grep -Iqn -e "$beside" "$root/$f"; then
      grep -In -e "$beside" "$root/$f" | sed "s#^#$f:#" | head -5
      echo "$f: points at a folder beside the repository, which a clone does not have"
      bad=1
    fi
  done < <(files_of "$root")
  if ! head -5 "$root/LICENSE" 2>/dev/null | grep -q 'Apache License' || ! grep -q 'Version 2.0, January 2004' "$root/LICENSE"; then
    echo "LICENSE: not the Apache License 2.0"
    bad=1
  fi
  if ! grep -qx "version: $version" "$root/CITATION.cff" 2>/dev/null; then
    echo "CITATION.cff: no 'version: $version' (the project's version)"
    bad=1
  fi
  grep -q 'Modeling the Linux page cache for accurate simulation of data-intensive applications' "$root/CITATION.cff" 2>/dev/null ||
    { echo "CITATION.cff: does not cite the paper pcsim builds on"; bad=1; }
  local dir
  for dir in "$root"/inputs/*/; do
    dir=${dir%/}
    if [ ! -f "$dir/README.md" ] || ! grep -q 'https://github.com/' "$dir/README.md" || ! grep -qi 'licen[cs]e' "$dir/README.md"; then
      echo "${dir#$root/}: no README.md naming its source (a URL) and its licence"
      bad=1
    fi
    if ! compgen -G "$dir/COPYING*" >/dev/null; then
      echo "${dir#$root/}: no COPYING* file with its licence's text"
      bad=1
    fi
  done
  grep -q '^\*\*Licence\.\*\*' "$root/validation/paper/README.md" 2>/dev/null ||
    { echo "validation/paper/README.md: does not say what licence its files are under"; bad=1; }
  return $bad
}

if [ "${1:-}" = --self-test ]; then
  root=$2 version=$3
  check "$root" "$version"
  # A planted pointer beside the repository, in a copy, is caught; so is a missing licence.
  copy=$(mktemp -d)
  trap 'rm -rf "$copy"' EXIT
  mkdir -p "$copy/inputs/x" "$copy/validation/paper"
  cp "$root/LICENSE" "$root/CITATION.cff" "$copy/"
  cp "$root/validation/paper/README.md" "$copy/validation/paper/"
  printf 'From https://github.com/a/b, licence LGPL\n' >"$copy/inputs/x/README.md"
  touch "$copy/inputs/x/COPYING"
  check "$copy" "$version" >/dev/null || { echo "self-test: the clean copy is refused"; exit 1; }
  printf 'see %s/reference\n' "../""shared" >"$copy/notes.txt"
  if check "$copy" "$version" >/dev/null; then echo "self-test: a planted pointer beside the repository is not caught"; exit 1; fi
  rm "$copy/notes.txt" "$copy/inputs/x/COPYING"
  if check "$copy" "$version" >/dev/null; then echo "self-test: an input folder without its licence is not caught"; exit 1; fi
  echo "self-test: planted faults caught"
else
  check "$1" "$2"
fi
