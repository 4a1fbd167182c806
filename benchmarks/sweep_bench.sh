#!/usr/bin/env bash
# How `pcsim sweep run` scales with --jobs, and what it costs per run beside the simulation:
# a sweep of 10,000 small runs (one Exp 2 pipeline, its CPU time x file size swept) run with
# --jobs 1 and --jobs 2 in turn, REPS times each, into fresh folders; prints each time, the
# medians, their ratio, and per run: the wall time, the time inside the run (scenario loaded,
# simulated, its line formatted) and the simulation's own.
#
#   benchmarks/sweep_bench.sh [PCSIM] [REPS]      (PCSIM: build/bin/pcsim)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
pcsim=${1:-$root/build/bin/pcsim}
reps=${2:-5}
work=$(mktemp -d "${TMPDIR:-/tmp}/pcsim-sweep-bench.XXXXXX")
trap 'rm -rf "$work"' EXIT
cat >"$work/small.toml" <<SWEEP
scenario = "$root/scenarios/paper/exp2.toml"
[[axes]]
key = "pipelines.count"
values = [1]
[[axes]]
key = "pipelines.cpu_time"
range = { from = 1, to = 100, step = 1 }
[[axes]]
key = "pipelines.file_size"
range = { from = 10000000, to = 1000000000, step = 10000000 }
SWEEP
runs=$("$pcsim" sweep plan "$work/small.toml" | wc -l)
seconds() {  # the wall time of a sweep of every run into a fresh folder
  rm -rf "$work/out"
  local start end
  start=$(date +%s.%N)
  "$pcsim" sweep run "$work/small.toml" --out "$work/out" --jobs "$1" --quiet
  end=$(date +%s.%N)
  echo "$end - $start" | bc -l
}
median() { sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2}'; }
one=() two=()
for _ in $(seq 1 "$reps"); do
  one+=("$(seconds 1)")
  two+=("$(seconds 2)")
done
m1=$(printf '%s\n' "${one[@]}" | median)
m2=$(printf '%s\n' "${two[@]}" | median)
echo "runs: $runs, $(nproc) cores"
echo "--jobs 1: ${one[*]} s; median $m1 s"
echo "--jobs 2: ${two[*]} s; median $m2 s"
printf 'speed-up --jobs 2 over --jobs 1 (medians): %.2fx\n' "$(echo "$m1 / $m2" | bc -l)"
# Per run, from the last --jobs 2 sweep's results and the --jobs 1 median.
"$pcsim" sweep merge "$work/out" >/dev/null
awk -F, -v total="$m1" -v runs="$runs" 'NR > 1 { w += $(NF - 1); s += $NF }
  END { printf "per run (--jobs 1): %.1f us of wall time; inside the run %.1f us, of which the simulation %.1f us\n",
        total / runs * 1e6, w / (NR - 1) * 1e6, s / (NR - 1) * 1e6 }' "$work/out/results.csv"
