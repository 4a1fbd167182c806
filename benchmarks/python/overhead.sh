#!/usr/bin/env bash
# pcsim.run against the same run through the C++ API, in alternation: ROUNDS rounds of one
# process each (REPS timed calls in it, the median), and the ratio of each round's medians.
#   benchmarks/python/overhead.sh [SCENARIO] [ROUNDS] [REPS] [KEY=VALUE ...]   (from a Release build/)
set -euo pipefail
cd "$(dirname "$0")/../.."
scenario=${1:-scenarios/paper/exp2.toml} rounds=${2:-10} reps=${3:-50}
shift $(( $# < 3 ? $# : 3 ))
ratios=()
for ((i = 0; i < rounds; i++)); do
  py=$(PYTHONPATH=build/python /usr/bin/python3 benchmarks/python/run_call.py "$scenario" "$reps" "$@")
  cpp=$(build/benchmarks/api_run "$scenario" "$reps" "$@")
  ratio=$(echo "scale=4; $py / $cpp" | bc)
  ratios+=("$ratio")
  echo "round $i: pcsim.run $py s, C++ API $cpp s, ratio $ratio"
done
printf '%s\n' "${ratios[@]}" | sort -n | awk '{a[NR]=$1} END {print "ratio min " a[1] ", median " a[int((NR+1)/2)] ", max " a[NR]}'
