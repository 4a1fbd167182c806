#!/usr/bin/env bash
# pcsim sweep, run as users run it: the paper's Exp 2 over 128 runs (a) in one process with
# --jobs 2 and (b) as four shards started by GNU parallel from `sweep plan --commands` must
# merge into the same results.csv but for the wall times; (c) a shard killed mid-way and run
# again completes its sweep with each run exactly once; (d) bad sweep files exit 2 naming the
# axis, with no results folder made; (e) a results file pcsim did not write is refused and left
# as it is; (f) a folder holds one sweep: results of another base, or of this base edited since,
# are refused naming what changed, and any mix of shard splits runs each run once; (g) merge
# --csv names its option, and never replaces what merge reads.
#
#   sweep_test.sh PCSIM_BINARY SOURCE_DIR
set -euo pipefail
pcsim=$1
source_dir=$2
here=$(cd "$(dirname "$0")" && pwd)
. "$here/sweep_exp2.sh"
command -v parallel >/dev/null || { echo "GNU parallel is missing (scripts/install-deps installs it)"; exit 1; }
work=$(mktemp -d "${TMPDIR:-/tmp}/pcsim-sweep.XXXXXX")
trap 'kill $(jobs -p) 2>/dev/null || true; rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

exp2=$(exp2_sweep_file "$source_dir")

# (a) One process, two runs at a time.
"$pcsim" sweep run "$exp2" --out "$work/a" --jobs 2 --quiet
"$pcsim" sweep merge "$work/a" >/dev/null
[ "$(wc -l <"$work/a/results.csv")" = 129 ] || fail "(a): $(wc -l <"$work/a/results.csv") lines, expected a header and 128 runs"
[ "$(grep -c ',ok,0,' "$work/a/results.csv")" = 128 ] || fail "(a): not every run ended well"

# (b) Four shards, one command line each, run by GNU parallel.
"$pcsim" sweep plan "$exp2" --commands --shards 4 --out "$work/b" >"$work/commands"
[ "$(wc -l <"$work/commands")" = 4 ] || fail "(b): $(wc -l <"$work/commands") command lines, expected 4"
parallel --will-cite --halt now,fail=1 -j 2 <"$work/commands" >/dev/null
ls "$work/b"/results-*-of-4.jsonl >/dev/null
"$pcsim" sweep merge "$work/b" >/dev/null
cmp <(without_wall_times "$work/a/results.csv") <(without_wall_times "$work/b/results.csv") || fail "(b): results.csv differs from (a)'s"

# `sweep plan` lists every run, id first; --keep-outputs writes each run's own folder.
[ "$("$pcsim" sweep plan "$exp2" | wc -l)" = 128 ] || fail "sweep plan does not list 128 runs"
first=$("$pcsim" sweep plan "$exp2" | sed -n 1p)  # sed reads it all: head would cut pcsim off with SIGPIPE
[ "$first" = "$(head -2 "$work/a/results.csv" | tail -1 | cut -d, -f1) pipelines.count=1 hosts.0.page_cache.dirty_ratio=0.2 'hosts.0.memory=\"128 GB\"'" ] ||
  fail "sweep plan's first line: $first"
cat >"$work/two.toml" <<SWEEP
scenario = "$source_dir/scenarios/paper/exp2.toml"
[[points]]
"pipelines.count" = 2
[[points]]
"pipelines.count" = 3
SWEEP
"$pcsim" sweep run "$work/two.toml" --out "$work/kept" --keep-outputs --quiet
[ "$(ls "$work/kept/runs" | wc -l)" = 2 ] || fail "--keep-outputs: $(ls "$work/kept/runs" | wc -l) run folders, expected 2"
for run in "$work/kept/runs"/*; do
  [ -s "$run/summary.json" ] && [ -s "$run/timeline.csv" ] || fail "--keep-outputs: $run lacks its outputs"
done

# A sweep grown by an axis value goes on in the same folder: only the new runs run.
grown="$work/grown.toml"
sed 's/values = \["128 GB", "256 GB"\]/values = ["128 GB", "256 GB", "192 GB"]/; s|"../paper/exp2.toml"|"'"$source_dir"'/scenarios/paper/exp2.toml"|' "$exp2" >"$grown"
cp -r "$work/a" "$work/a2"
"$pcsim" sweep run "$grown" --out "$work/a2" --jobs 2 >"$work/grown.out"
grep -q "64 runs done (0 failed), 128 already there" "$work/grown.out" || fail "the grown sweep: $(cat "$work/grown.out")"
"$pcsim" sweep merge "$work/a2" >/dev/null
[ "$(wc -l <"$work/a2/results.csv")" = 193 ] || fail "the grown sweep: $(wc -l <"$work/a2/results.csv") lines, expected 193"
# A different sweep into a folder of this one's is refused, naming a run it would lose.
status=0
"$pcsim" sweep run "$work/two.toml" --out "$work/a" --quiet 2>"$work/other.err" || status=$?
[ "$status" = 2 ] && grep -q "another base scenario\|runs this one lacks" "$work/other.err" || fail "another sweep into (a)'s folder: exit $status, $(cat "$work/other.err")"
# The same runs of another base (the linux profile) are other runs: refused too.
sed 's/^scenario = .*/&\nprofile = "linux"/' "$grown" >"$work/linux.toml"
status=0
"$pcsim" sweep run "$work/linux.toml" --out "$work/a2" --quiet 2>"$work/linux.err" || status=$?
[ "$status" = 2 ] && grep -q "another base scenario" "$work/linux.err" || fail "another base into (a2): exit $status, $(cat "$work/linux.err")"

# (c) A shard killed while it runs, then run again: every run once. Runs of 1 MB chunks take
# long enough to kill the shard part way.
cat >"$work/slow.toml" <<SWEEP
scenario = "$source_dir/scenarios/paper/exp2.toml"
profile = "linux"
[[axes]]
key = "pipelines.chunk_size"
values = ["1 MB"]
[[axes]]
key = "pipelines.count"
range = { from = 1, to = 24, step = 1 }
SWEEP
"$pcsim" sweep run "$work/slow.toml" --out "$work/c" --jobs 1 --quiet &
shard=$!
for _ in $(seq 1 600); do
  [ -f "$work/c/results-0-of-1.jsonl" ] && [ "$(wc -l <"$work/c/results-0-of-1.jsonl")" -ge 5 ] && break
  sleep 0.05
done
kill -9 "$shard"
wait "$shard" 2>/dev/null || true
before=$(wc -l <"$work/c/results-0-of-1.jsonl")
{ [ "$before" -ge 5 ] && [ "$before" -lt 24 ]; } || fail "(c): the shard was killed after $before of 24 runs, not part way"
if "$pcsim" sweep merge "$work/c" 2>"$work/c.err"; then fail "(c): merge accepted a sweep with runs missing"; fi
grep -q "runs have no result yet" "$work/c.err" || fail "(c): merge did not name the missing runs: $(cat "$work/c.err")"
"$pcsim" sweep run "$work/slow.toml" --out "$work/c" --jobs 1 --quiet
"$pcsim" sweep merge "$work/c" >/dev/null  # refuses duplicated runs
[ "$(wc -l <"$work/c/results.csv")" = 25 ] || fail "(c): $(wc -l <"$work/c/results.csv") lines after the rerun, expected 25"
[ "$(cut -d, -f1 "$work/c/results.csv" | sort | uniq -d | wc -l)" = 0 ] || fail "(c): a run is there twice"
[ "$(grep -c ',ok,0,' "$work/c/results.csv")" = 24 ] || fail "(c): not every run ended well"

# (d) Bad sweep files: exit 2, the axis named, no results folder.
bad() {
  local name=$1 axis=$2 body=$3
  printf 'scenario = "%s/scenarios/paper/exp2.toml"\n%s\n' "$source_dir" "$body" >"$work/$name.toml"
  local status=0
  "$pcsim" sweep run "$work/$name.toml" --out "$work/$name-out" --quiet 2>"$work/$name.err" || status=$?
  [ "$status" = 2 ] || fail "($name): exit $status, expected 2"
  grep -q -F "$axis" "$work/$name.err" || fail "($name): the message does not name $axis: $(cat "$work/$name.err")"
  [ ! -e "$work/$name-out" ] || fail "($name): a results folder was made"
}
bad unknown_key "pipelines.colour" $'[[axes]]\nkey = "pipelines.colour"\nvalues = [1]'
bad empty_axis "axis 'pipelines.count'" $'[[axes]]\nkey = "pipelines.count"\nvalues = []'
bad wrong_type "axis 'hosts.0.memory'" $'[[axes]]\nkey = "hosts.0.memory"\nvalues = [true]'
bad step_zero "axis 'pipelines.count'" $'[[axes]]\nkey = "pipelines.count"\nrange = { from = 1, to = 3, step = 0 }'

# A log range of 34657361 steps is refused at once (it took 20 s and 1.6 GB), and a step that
# is not a number says so.
bad factor_tiny "by factor 1.0000001 makes 34657361 values" $'[[axes]]\nkey = "pipelines.count"\nrange = { from = 1, to = 32, factor = 1.0000001 }'
bad step_nan "step = nan is not a number" $'[[axes]]\nkey = "pipelines.count"\nrange = { from = 1, to = 3, step = nan }'

# (e) Results files pcsim did not write: refused, left as they are.
mkdir -p "$work/e/base"
sed 's|"\.\./\.\./platforms/|"'"$source_dir"'/platforms/|g' "$source_dir/scenarios/paper/exp2.toml" >"$work/e/base/exp2.toml"
small() {  # small FILE VALUES [SCENARIO]: a sweep of pipelines.count over VALUES
  printf 'scenario = "%s"\n[[axes]]\nkey = "pipelines.count"\nvalues = [%s]\n' "${3:-$work/e/base/exp2.toml}" "$2" >"$1"
}
small "$work/e/two.toml" "1, 2"
refused() {  # refused NAME MESSAGE COMMAND...: exit 2, MESSAGE on stderr
  local name=$1 message=$2 status=0
  shift 2
  "$@" >/dev/null 2>"$work/e/$name.err" || status=$?
  [ "$status" = 2 ] && grep -q -F -- "$message" "$work/e/$name.err" || fail "($name): exit $status, $(cat "$work/e/$name.err")"
}
mkdir "$work/e/hello"
printf 'hello\nworld' >"$work/e/hello/results-0-of-1.jsonl"
refused hello "results-0-of-1.jsonl:1: not a result pcsim wrote" "$pcsim" sweep run "$work/e/two.toml" --out "$work/e/hello" --quiet
[ "$(cat "$work/e/hello/results-0-of-1.jsonl")" = "$(printf 'hello\nworld')" ] || fail "(hello): the file was changed"
mkdir "$work/e/link"
printf '{"id": "x"}\npartial' >"$work/e/elsewhere.jsonl"
ln -s ../elsewhere.jsonl "$work/e/link/results-0-of-1.jsonl"
refused link "results-0-of-1.jsonl: is a symbolic link" "$pcsim" sweep run "$work/e/two.toml" --out "$work/e/link" --quiet
mkdir "$work/e/hard"
ln "$work/e/elsewhere.jsonl" "$work/e/hard/results-0-of-1.jsonl"
refused hard "results-0-of-1.jsonl: has 2 hard links" "$pcsim" sweep run "$work/e/two.toml" --out "$work/e/hard" --quiet
[ "$(cat "$work/e/elsewhere.jsonl")" = "$(printf '{"id": "x"}\npartial')" ] || fail "(link, hard): the file they name was changed"

# (f) One sweep per folder. A results file of another base, copied in: refused by merge.
sed 's/cpu_time = "4.4 s"/cpu_time = "5 s"/' "$work/e/base/exp2.toml" >"$work/e/base/other.toml"
small "$work/e/other.toml" "1, 2" "$work/e/base/other.toml"
"$pcsim" sweep run "$work/e/two.toml" --out "$work/e/A" --quiet
"$pcsim" sweep run "$work/e/other.toml" --out "$work/e/B" --quiet
mv "$work/e/B/results-0-of-1.jsonl" "$work/e/A/results-0-of-2.jsonl"
rm "$work/e/A/results-0-of-1.jsonl"
refused copied "results-0-of-2.jsonl:1: the result of a run of another sweep" "$pcsim" sweep merge "$work/e/A"
# The base edited, then the sweep grown: refused, naming the file.
"$pcsim" sweep run "$work/e/two.toml" --out "$work/e/C" --quiet
sed -i 's/cpu_time = "4.4 s"/cpu_time = "9 s"/' "$work/e/base/exp2.toml"
small "$work/e/three.toml" "1, 2, 3"
refused edited "$work/e/base/exp2.toml (the scenario file) has changed" "$pcsim" sweep run "$work/e/three.toml" --out "$work/e/C" --quiet
sed -i 's/cpu_time = "9 s"/cpu_time = "4.4 s"/' "$work/e/base/exp2.toml"
# Shards of 3, then the grown sweep without --shard: only its new run runs.
for i in 0 1 2; do "$pcsim" sweep run "$work/e/three.toml" --out "$work/e/D" --shard "$i/3" --quiet; done
small "$work/e/four.toml" "1, 2, 3, 4"
"$pcsim" sweep run "$work/e/four.toml" --out "$work/e/D" >"$work/e/four.out"
grep -q "1 runs done (0 failed), 3 already there" "$work/e/four.out" || fail "(shards): $(cat "$work/e/four.out")"
"$pcsim" sweep merge "$work/e/D" >/dev/null || fail "(shards): merge refused"

# (g) merge --csv names its option; an empty one, or one of merge's inputs, is refused.
mkdir "$work/e/a-folder"
refused csv "--csv $work/e/a-folder: is a folder" "$pcsim" sweep merge "$work/e/C" --csv "$work/e/a-folder"
refused csv-empty "--csv : no file named" "$pcsim" sweep merge "$work/e/C" --csv ''
# Nor may --csv take the place of what merge reads: the files stay as they were.
cp "$work/e/C/results-0-of-1.jsonl" "$work/e/C-results.kept"
refused csv-input "--csv $work/e/C/results-0-of-1.jsonl: is $work/e/C/results-0-of-1.jsonl, which pcsim reads" \
  "$pcsim" sweep merge "$work/e/C" --csv "$work/e/C/results-0-of-1.jsonl"
cmp -s "$work/e/C/results-0-of-1.jsonl" "$work/e/C-results.kept" || fail "(csv-input): the results file was changed"
ln -s C/sweep-plan.json "$work/e/plan-link"
refused csv-plan "which pcsim reads" "$pcsim" sweep merge "$work/e/C" --csv "$work/e/plan-link"

echo "sweep tests: $failures failures"
[ "$failures" = 0 ]
