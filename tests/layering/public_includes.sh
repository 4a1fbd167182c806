#!/usr/bin/env bash
# The layer fence. The build gives each layer of src/ an include root holding only itself and
# the layers below it (cmake/Layers.cmake), but every layer sees all of include/pagecache/:
# this checks that a public header, and a source file of a layer, includes only public headers
# of its own layer or of those below (the BELOW lists of src/CMakeLists.txt), and that its
# includes of src/ stay within what it sees too (so that a format's room, src/formats/*, reaches
# nothing but formats/common, even if the build's fence were loosened). Every public header must
# be given a layer here.
#
#   public_includes.sh SOURCE_DIR          # exit 1 naming each upward include
#   public_includes.sh --self-test SOURCE_DIR  # also: upward includes planted in a copy are caught
set -euo pipefail

# The layer of each public header. The exception types (error) are every layer's vocabulary:
# below all of them, as the generated version header is.
declare -A layer_of=(
  [error]=text [task]=engine [simulator]=engine [event]=engine [timer]=engine
  [memory_state]=engine [trace]=engine
  [units]=formats/common
  [fair_share]=storage [devices]=storage
  [cache_settings]=cache [cache_policies]=cache [host]=cache
  [run]=workload [scenario]=workload
  [scenario_file]=scenario
  [outputs]=report
)

# Each layer and what it sees, one line each: "NAME BELOW...", from src/CMakeLists.txt (a
# layer's BELOW list may continue on the next lines, up to SOURCES).
layers() {
  awk '/^pagecache_add_layer\(/ { open = 1; line = $0; next }
       open && /^ *SOURCES/ { open = 0; print line; next }
       open { line = line " " $0 }' "$1/src/CMakeLists.txt" |
    sed -E 's/^pagecache_add_layer\(([a-z_/]+)( BELOW)?/\1/; s/ +/ /g'
}

check() {
  local root=$1 bad=0
  # Each layer and what it may see: itself and its BELOW list.
  declare -A sees=()
  while read -r name below; do sees[$name]=" $name $below "; done < <(layers "$root")
  # The layer a path of src/ belongs to: the longest layer name it starts with.
  layer_of_path() {
    local path=$1 best="" name
    for name in "${!sees[@]}"; do
      [[ $path == "$name"/* && ${#name} -gt ${#best} ]] && best=$name
    done
    echo "$best"
  }
  # `file layer`: every pagecache/ include of `file`, and every include of src/, must be
  # visible from `layer`.
  fence() {
    local file=$1 layer=$2 header target path
    for path in $(sed -nE 's/^#include "([a-z_/]+\.hpp)".*/\1/p' "$file"); do
      target=$(layer_of_path "$path")
      [ -z "$target" ] && continue  # a header of the file's own folder
      if [[ ${sees[$layer]} != *" $target "* ]]; then
        echo "$file: a $layer file includes $path, of the $target layer, which it does not see"
        bad=1
      fi
    done
    for header in $(sed -nE 's/^#include <pagecache\/([a-z_]+)\.hpp>.*/\1/p' "$file"); do
      [ "$header" = version ] || [ "$header" = error ] && continue  # below everything
      target=${layer_of[$header]:-}
      if [ -z "$target" ]; then
        echo "$file: includes pagecache/$header.hpp, which has no layer in $0"
        bad=1
      elif [[ ${sees[$layer]} != *" $target "* ]]; then
        echo "$file: a $layer file includes pagecache/$header.hpp, of the $target layer above it"
        bad=1
      fi
    done
  }
  local h name
  for h in "$root"/include/pagecache/*.hpp; do
    name=$(basename "$h" .hpp)
    if [ -z "${layer_of[$name]:-}" ]; then
      echo "$h: a public header without a layer: give it one in $0"
      bad=1
      continue
    fi
    fence "$h" "${layer_of[$name]}"
  done
  local layer f
  for layer in "${!sees[@]}"; do
    [ -d "$root/src/$layer" ] || continue
    for f in "$root/src/$layer"/*.cpp "$root/src/$layer"/*.hpp; do
      [ -e "$f" ] && fence "$f" "$layer"
    done
  done
  return $bad
}

if [ $# -eq 0 ]; then
  echo "usage: public_includes.sh [--self-test] SOURCE_DIR" >&2
  exit 2
fi
if [ "$1" = --self-test ]; then
  root=$2
  check "$root"
  # A copy with one upward include (the page cache's block reaching up to the runner's API)
  # must be refused.
  copy=$(mktemp -d "${TMPDIR:-/tmp}/pcsim-layers.XXXXXX")
  trap 'rm -rf "$copy"' EXIT
  mkdir -p "$copy/src"
  cp -r "$root/include" "$copy/"
  cp -r "$root/src/." "$copy/src/"
  echo '#include <pagecache/run.hpp>' >>"$copy/src/cache/block.hpp"
  # A format's room reaching for the scenario loader, and for another format's room.
  echo '#include "scenario/toml_reader.hpp"' >>"$copy/src/formats/fio/syntax.hpp"
  echo '#include "formats/fio/job_file.hpp"' >>"$copy/src/formats/wfformat/links.hpp"
  if check "$copy" >"$copy/out"; then
    echo "the planted upward includes were not caught"
    exit 1
  fi
  for expected in "src/cache/block.hpp: a cache file includes pagecache/run.hpp, of the workload layer above it" \
    "src/formats/fio/syntax.hpp: a formats/fio file includes scenario/toml_reader.hpp, of the scenario layer, which it does not see" \
    "src/formats/wfformat/links.hpp: a formats/wfformat file includes formats/fio/job_file.hpp, of the formats/fio layer, which it does not see"; do
    grep -qF "$expected" "$copy/out" || {
      echo "not caught: $expected"
      cat "$copy/out"
      exit 1
    }
  done
  echo "the layers hold, and planted upward includes are caught"
else
  check "$1"
fi
