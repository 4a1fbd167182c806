#!/usr/bin/env bash
# pcsim calibrate, run as a user runs it, at a tiny scale (--quick, 16 MiB files): (a) it
# writes a platform file pcsim loads, with every value of the host and its disk, and leaves
# the folder as it found it; (b) a folder that does not exist, a file given as the folder, and
# a size the file system has no room for are refused with exit 2, naming them, and nothing is
# written; (c) when run by root, the same as the ordinary user nobody, which says what it
# could not do as root. No figure is judged: they measure this machine.
#
#   calibrate_test.sh PCSIM_BINARY
set -euo pipefail
pcsim=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
work=$(mktemp -d "${TMPDIR:-/tmp}/pcsim-calibrate.XXXXXX")
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# (a) As this user.
mkdir "$work/dir"
echo "mine" >"$work/dir/keep.txt"
"$pcsim" calibrate --quick --size "16 MiB" --dir "$work/dir" --out "$work/platform.toml" >"$work/summary.txt" 2>&1 ||
  { cat "$work/summary.txt"; fail "(a): calibrate failed"; }
for key in 'cores = ' 'memory = ' 'memory_read_bw = ' 'memory_write_bw = ' 'memory_first_touch_bw = ' 'dirty_ratio = ' \
  'read_bw = ' 'write_bw = ' 'aggregate_read_bw = ' 'aggregate_write_bw = '; do
  grep -q "^$key" "$work/platform.toml" || fail "(a): the platform file has no '$key'"
done
grep -q "memory_reclaimed_write_bw not set: not measured with --quick" "$work/platform.toml" || fail "(a): reclaim not said to be skipped"
grep -q "disk read, one stream" "$work/summary.txt" || fail "(a): no summary"
[ "$(ls -A "$work/dir")" = keep.txt ] || fail "(a): the folder was left with: $(ls -A "$work/dir" | tr '\n' ' ')"
[ "$(cat "$work/dir/keep.txt")" = mine ] || fail "(a): a file of the user's changed"
# pcsim runs a scenario on it.
cat >"$work/run.toml" <<TOML
platform = "platform.toml"
[pipelines]
file_size = "1 GB"
tasks = 1
TOML
"$pcsim" run "$work/run.toml" --out "$work/out" --quiet || fail "(a): pcsim cannot run on the calibrated platform"
[ -s "$work/out/summary.json" ] || fail "(a): no summary.json from the run on the calibrated platform"
# Without --out: the platform file on the standard output, the summary on the standard error.
"$pcsim" calibrate --quick --size "16 MiB" --dir "$work/dir" >"$work/stdout.toml" 2>"$work/stderr.txt" || fail "(a): calibrate to stdout failed"
grep -q '^\[\[hosts.disks\]\]' "$work/stdout.toml" || fail "(a): no platform on the standard output"
grep -q "disk read, one stream" "$work/stderr.txt" || fail "(a): no summary on the standard error"

# Repeated measurements: the median of each, the rates and their spread said above it.
"$pcsim" calibrate --quick --repeat 2 --size "16 MiB" --dir "$work/dir" --out "$work/twice.toml" >/dev/null 2>&1 || fail "(a): --repeat 2 failed"
grep -q "median of 2 (" "$work/twice.toml" || fail "(a): --repeat 2 does not say it took a median of 2"
[ "$(ls -A "$work/dir")" = keep.txt ] || fail "(a): --repeat 2 left in the folder: $(ls -A "$work/dir" | tr '\n' ' ')"

# (b) Refused, exit 2, naming what is wrong; no platform written.
expect_refused() {
  local what=$1 pattern=$2
  shift 2
  local status=0
  "$pcsim" calibrate --quick "$@" --out "$work/refused.toml" >"$work/refused.txt" 2>&1 || status=$?
  [ "$status" = 2 ] || fail "($what): exit $status, expected 2: $(cat "$work/refused.txt")"
  grep -q -- "$pattern" "$work/refused.txt" || fail "($what): the message does not say '$pattern': $(cat "$work/refused.txt")"
  [ ! -e "$work/refused.toml" ] || fail "($what): a platform file was written"
}
expect_refused "no folder" "not a folder" --dir "$work/nowhere"
expect_refused "a file" "not a folder" --dir "$work/dir/keep.txt"
expect_refused "no room" "calibrate writes up to" --dir "$work/dir" --size "1 PB"
expect_refused "bad size" "--size" --dir "$work/dir" --size "lots"
[ "$(ls -A "$work/dir")" = keep.txt ] || fail "(b): the folder was left with: $(ls -A "$work/dir" | tr '\n' ' ')"

# (c) As an ordinary user, when this is root.
if [ "$(id -u)" = 0 ] && id nobody >/dev/null 2>&1; then
  mkdir "$work/nobody"
  chmod 755 "$work"
  chown nobody "$work/nobody"
  setpriv --reuid=nobody --regid="$(id -g nobody)" --clear-groups \
    "$pcsim" calibrate --quick --size "16 MiB" --dir "$work/nobody" >"$work/nobody.toml" 2>"$work/nobody.txt" ||
    { cat "$work/nobody.txt"; fail "(c): calibrate as nobody failed"; }
  grep -q "not root" "$work/nobody.txt" || fail "(c): as nobody it does not say what it could not do"
  grep -q '^read_bw = ' "$work/nobody.toml" || fail "(c): no platform as nobody"
  [ -z "$(ls -A "$work/nobody")" ] || fail "(c): nobody's folder was left with: $(ls -A "$work/nobody" | tr '\n' ' ')"
fi

[ "$failures" = 0 ] && echo "calibrate: all checks passed"
exit "$failures"
