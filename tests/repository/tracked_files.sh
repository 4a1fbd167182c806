#!/usr/bin/env bash
# What a clone carries is source, small: no file over 1 MB (a core dump once made a clone 20 MB,
# 19 of them the dump), and no binary file but the documentation's images and the fuzzers'
# regression inputs (which hold the bytes that broke a reader).
#
#   tracked_files.sh SOURCE_DIR               # exit 1 naming each fault
#   tracked_files.sh --self-test SOURCE_DIR   # also: a planted large file and a planted binary are caught
set -euo pipefail
# shellcheck source=files_of.sh
source "$(dirname "$0")/files_of.sh"

readonly max_bytes=1000000

# Binary files a clone may hold, as shell patterns of their paths.
allowed_binary() {
  case $1 in
    docs/*.png | docs/*.svg | tests/fuzz/regressions/*) return 0 ;;
    *) return 1 ;;
  esac
}

check() {
  local root=$1 bad=0 f size
  while IFS= read -r f; do
    [ -f "$root/$f" ] || continue
    size=$(stat -c %s "$root/$f")
    if [ "$size" -gt "$max_bytes" ]; then
      echo "$f: $size bytes, over the 1 MB a tracked file may have"
      bad=1
    fi
    # grep -I takes a file with a NUL byte for binary; an empty file is text.
    if [ "$size" -gt 0 ] && ! grep -Iq . "$root/$f" && ! allowed_binary "$f"; then
      echo "$f: a binary file, and not one a clone may hold (docs' images, fuzz regressions)"
      bad=1
    fi
  done < <(files_of "$root")
  return $bad
}

if [ "${1:-}" = --self-test ]; then
  root=$2
  check "$root"
  copy=$(mktemp -d)
  trap 'rm -rf "$copy"' EXIT
  mkdir -p "$copy/docs" "$copy/tests/fuzz/regressions"
  printf 'text\n' >"$copy/README.md"
  printf '\x89PNG\r\n\x1a\n\0' >"$copy/docs/figure.png"
  printf 'a\0b' >"$copy/tests/fuzz/regressions/x"
  check "$copy" >/dev/null || { echo "self-test: the clean copy is refused"; exit 1; }
  head -c 2000000 /dev/zero | tr '\0' 'x' >"$copy/big.txt"
  if check "$copy" >/dev/null; then echo "self-test: a planted file of 2 MB is not caught"; exit 1; fi
  rm "$copy/big.txt"
  printf '\x7fELF\0\0' >"$copy/core"
  if check "$copy" >/dev/null; then echo "self-test: a planted binary file is not caught"; exit 1; fi
  echo "self-test: planted faults caught"
else
  check "$1"
fi
