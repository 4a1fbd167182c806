#!/usr/bin/env bash
# Someone else's program built against pagecache as the field builds against libraries: with
# find_package(pagecache) from the build tree and from an install prefix, and with pkg-config;
# the library static (the project's own build) or shared (the build's shared twin, the same
# objects linked as libpagecache.so). Each program runs a shipped scenario through the public API
# (pagecache/outputs.hpp) and must write every output `pcsim run` writes, byte for byte (all
# but timing.json, the simulator's own wall time). The shared flavour also runs the installed
# pcsim from another folder: it finds its library and its data relative to itself.
#
#   consumer_test.sh static|shared SOURCE_DIR BINARY_DIR WORK_DIR BUILD_TYPE
set -euo pipefail
flavour=$1 source=$2 binary=$3 work=$4 build_type=$5
scenario=$source/scenarios/paper/exp2.toml
outputs=(timeline.csv memory.csv cache.csv summary.json report.html)

rm -rf "$work"
mkdir -p "$work"
cd "$work"
fail() { echo "FAIL: $*"; exit 1; }

# What pcsim run writes: the reference every program is held to.
"$binary/bin/pcsim" run "$scenario" --out "$work/reference" --quiet
same_outputs() {  # same_outputs DIR WHAT
  local f
  for f in "${outputs[@]}"; do
    [ -s "$1/$f" ] || fail "$2 wrote no $f"
    cmp -s "$work/reference/$f" "$1/$f" || fail "$2 wrote a $f that differs from pcsim run's"
  done
  echo "ok: $2 writes what pcsim run writes (${outputs[*]})"
}

# A consumer project configured with CMAKE_ARGS..., built, then run twice: the engine alone
# (four readers share a disk: done at 4 s), and the scenario with its outputs.
consumer() {  # consumer NAME CMAKE_ARGS...
  local name=$1
  shift
  cmake -S "$source/tests/consumer" -B "$work/$name" -DCMAKE_BUILD_TYPE="$build_type" "$@" >"$work/$name.log" 2>&1 ||
    { cat "$work/$name.log"; fail "$name: configuring the consumer"; }
  cmake --build "$work/$name" >>"$work/$name.log" 2>&1 || { cat "$work/$name.log"; fail "$name: building the consumer"; }
  check_program "$name" "$work/$name/consumer"
}
check_program() {  # check_program NAME PROGRAM
  local out
  out=$("$2") || fail "$1: the consumer failed: $out"
  [ "$out" = "done at 4 s" ] || fail "$1: the consumer printed '$out', not 'done at 4 s'"
  "$2" "$scenario" "$work/$1-out" >/dev/null || fail "$1: the consumer could not run $scenario"
  same_outputs "$work/$1-out" "$1"
}
linked_shared() {  # linked_shared PROGRAM: whether it loads libpagecache.so
  readelf -d "$1" | grep -q 'NEEDED.*libpagecache\.so'
}

case "$flavour" in
  static) config=$binary install=() ;;
  # The same objects linked as libpagecache.so by the build under test (cmake/Install.cmake).
  shared) config=$binary/shared-twin install=(--component shared-twin) ;;
  *) echo "usage: consumer_test.sh static|shared SOURCE_DIR BINARY_DIR WORK_DIR BUILD_TYPE"; exit 2 ;;
esac

# 1. The build tree, not installed.
consumer build-tree -Dpagecache_DIR="$config"
# 2. An install prefix.
cmake --install "$binary" "${install[@]}" --prefix "$work/prefix" >"$work/install.log" 2>&1 || { cat "$work/install.log"; fail "cmake --install"; }
consumer prefix -DCMAKE_PREFIX_PATH="$work/prefix"
# 3. pkg-config, from the same prefix (the linker finds a shared library by an rpath here).
libdir=$(dirname "$(find "$work/prefix" -name pagecache.pc)")/..
export PKG_CONFIG_PATH=$libdir/pkgconfig
[ "$(pkg-config --modversion pagecache)" = "$(sed -nE 's/^project\(pcsim VERSION ([0-9.]+).*/\1/p' "$source/CMakeLists.txt")" ] ||
  fail "pkg-config --modversion pagecache: $(pkg-config --modversion pagecache)"
# shellcheck disable=SC2046
g++ -std=c++20 -O1 "$source/tests/consumer/consumer.cpp" -o "$work/pkg-config-consumer" $(pkg-config --cflags --libs pagecache) \
  -Wl,-rpath,"$(cd "$libdir" && pwd)" || fail "building with pkg-config --cflags --libs pagecache"
check_program pkg-config "$work/pkg-config-consumer"

# The library is what the flavour says, in every program.
for program in "$work/build-tree/consumer" "$work/prefix/consumer" "$work/pkg-config-consumer"; do
  if [ "$flavour" = shared ]; then
    linked_shared "$program" || fail "$program does not load libpagecache.so"
  else
    if linked_shared "$program"; then fail "$program loads libpagecache.so in the static flavour"; fi
  fi
done
[ "$flavour" = static ] || [ -n "$(find "$work/prefix" -name 'libpagecache.so*')" ] || fail "no libpagecache.so installed"
[ "$flavour" = shared ] || [ -n "$(find "$work/prefix" -name 'libpagecache.a')" ] || fail "no libpagecache.a installed"
echo "ok: $flavour library in every program"

# The installed pcsim, run from elsewhere: its library and data found relative to itself.
mkdir -p "$work/elsewhere"
cd "$work/elsewhere"
"$work/prefix/bin/pcsim" run "$scenario" --out installed --quiet || fail "the installed pcsim could not run"
same_outputs installed "the installed pcsim"
"$work/prefix/bin/pcsim" run "$work/prefix/share/pcsim/scenarios/paper/exp3.toml" --out shipped --quiet ||
  fail "the installed pcsim could not run its shipped exp3.toml"
"$work/prefix/bin/pcsim" validate --json v.json --report v.html >validate.txt || fail "the installed pcsim validate failed"
grep -q '"mean_error_pct"' v.json || fail "the installed pcsim validate wrote no errors to v.json"
echo "ok: the installed pcsim runs and validates from $work/elsewhere"
