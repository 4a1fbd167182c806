#!/usr/bin/env bash
# pcsim calibrate, run as a user runs it, at a tiny scale (--quick, 16 MiB files): (a) it
# writes a platform file pcsim loads, with every value of the host and its disk, the device's
# request latency, readahead and largest request where this machine has them (O_DIRECT, a
# block device or a bdi under the folder), each said how it was found, and leaves the folder as
# it found it; (b) a folder that does not exist, a file given as the folder, and
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
# The device's requests: what sysfs says of the folder's device (the disk's, for a partition),
# read as the kernel gives it; the latency and the write cache where O_DIRECT works there.
dev=$(stat -c '%Hd:%Ld' "$work/dir")
block=/sys/dev/block/$dev bdi=$dev
if [ -e "$block/partition" ]; then
  bdi=$(cat "$block/../dev")
  block=$block/..
fi
read_ahead=$(cat "/sys/class/bdi/$bdi/read_ahead_kb" 2>/dev/null || cat "$block/queue/read_ahead_kb" 2>/dev/null || true)
if [ -n "$read_ahead" ]; then
  grep -q "^read_ahead = \"$read_ahead KiB\"$" "$work/platform.toml" || fail "(a): no 'read_ahead = \"$read_ahead KiB\"' (sysfs's for $dev)"
  grep -q "^# the kernel's readahead window for this file system, read, not measured: /sys/" "$work/platform.toml" ||
    fail "(a): read_ahead's comment does not say where it was read"
else
  grep -q "^# read_ahead not set: " "$work/platform.toml" || fail "(a): no read_ahead and no word why ($dev has no bdi nor queue)"
fi
if [ -e "$block/queue/max_sectors_kb" ]; then
  grep -q "^max_request = \"$(cat "$block/queue/max_sectors_kb") KiB\"$" "$work/platform.toml" || fail "(a): no max_request as sysfs's for $dev"
else
  grep -q "^# max_request not set: " "$work/platform.toml" || fail "(a): no max_request and no word why ($dev is no block device)"
fi
if grep -q "refuses O_DIRECT" "$work/platform.toml"; then
  grep -q "^# request_latency not set: " "$work/platform.toml" || fail "(a): no O_DIRECT, and no word of request_latency"
else
  grep -q "^request_latency = \"[0-9.]* ms\"$" "$work/platform.toml" || fail "(a): no request_latency in ms"
  grep -q "^# O_DIRECT sequential reads of one .*, by request size" "$work/platform.toml" || fail "(a): no table of rates by request size"
  grep -q "^#     64 KiB " "$work/platform.toml" || fail "(a): the table has no 64 KiB row"
  grep -q "^# fitted as time per request = request_latency + size / bandwidth" "$work/platform.toml" || fail "(a): the fit is not said"
  grep -q "^# O_DIRECT sequential writes of random data, .* in pieces of .* rates in MB/s, in order:$" "$work/platform.toml" ||
    fail "(a): no write-cache pieces"
  grep -q "^# write_cache, sustained_write_bw not set: --quick" "$work/platform.toml" || fail "(a): --quick does not say it sets no write cache"
fi
grep -q "^# memory_cold_fault_bw, page_reporting_delay not set: " "$work/platform.toml" || fail "(a): --quick does not say why no cold fault rate"
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
