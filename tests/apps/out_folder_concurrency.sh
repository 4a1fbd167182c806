#!/usr/bin/env bash
# Pairs of `pcsim run`s started together by GNU parallel into one --out folder, as a parameter
# sweep would: every run must exit 0, or 2 with a message, and the folder must end up holding
# exactly one run's complete outputs, byte-identical (timing.json aside) to that variant's
# outputs made alone beforehand, with no staging folder left beside it. Half the pairs write a
# folder that does not exist yet, half replace a folder an earlier run made.
#
#   out_folder_concurrency.sh PCSIM_BINARY SCENARIO [PAIRS]     (30 pairs unless told)
#
# SCENARIO is tests/apps/golden/two_readers.toml, a run of a few milliseconds; its two variants
# differ in one task's compute time (2 s, as in the file, or 3 s), so their outputs differ.
set -euo pipefail
pcsim=$1
scenario=$2
pairs=${3:-30}
variants=(2 3)
command -v parallel >/dev/null || { echo "GNU parallel is missing (scripts/install-deps installs it)"; exit 1; }
work=$(mktemp -d "${TMPDIR:-/tmp}/pcsim-out-concurrency.XXXXXX")
trap 'rm -rf "$work"' EXIT

for variant in "${variants[@]}"; do
  "$pcsim" run "$scenario" --set "apps.0.tasks.0.compute=$variant" --out "$work/reference/$variant" --quiet
done
expected=$(ls -A "$work/reference/${variants[0]}")

mkdir "$work/logs"
for pair in $(seq 1 "$pairs"); do
  mkdir "$work/pair-$pair"
  if [ $((pair % 2)) = 0 ]; then cp -a "$work/reference/${variants[0]}" "$work/pair-$pair/out"; fi  # an earlier run's folder
done
# parallel starts a pair's second run some 20 ms after its first, about when the first ends: each
# run waits for the other to arrive, spinning (a sleep would part them by a millisecond again),
# for a second or two at most, so that the two write their folder at once.
parallel --will-cite -j2 --joblog "$work/logs/joblog" "
  touch '$work/logs/{1}-{2}.arrived'
  i=0
  until [ -e '$work/logs/{1}-${variants[0]}.arrived' ] && [ -e '$work/logs/{1}-${variants[1]}.arrived' ] || [ \$((i += 1)) -gt 1000000 ]; do :; done
  '$pcsim' run '$scenario' --set apps.0.tasks.0.compute={2} --out '$work/pair-{1}/out' --quiet > '$work/logs/{1}-{2}.log' 2>&1" \
  ::: $(seq 1 "$pairs") ::: "${variants[@]}" || true

# The variant whose reference `folder` matches, file for file (timing.json aside), or nothing.
matching_variant() {
  local folder=$1 variant name
  [ "$(ls -A "$folder" 2>/dev/null)" = "$expected" ] || return 0
  for variant in "${variants[@]}"; do
    for name in $expected; do
      [ "$name" = timing.json ] || cmp -s "$folder/$name" "$work/reference/$variant/$name" || continue 2
    done
    echo "$variant"
    return 0
  done
}

declare -A status=()
zeros=0
twos=0
failures=0
fail() { echo "pair $1: $2"; failures=$((failures + 1)); }
while read -r _ _ _ _ _ _ exitval signal command; do
  [[ $command =~ pair-([0-9]+)/out ]] && pair=${BASH_REMATCH[1]}
  [[ $command =~ compute=([0-9]+) ]] && variant=${BASH_REMATCH[1]}
  status[$pair-$variant]=$exitval
  case "$exitval/$signal" in
    0/0) zeros=$((zeros + 1)) ;;
    2/0) twos=$((twos + 1)); [ -s "$work/logs/$pair-$variant.log" ] || fail "$pair" "run $variant exited 2 without a message" ;;
    *) fail "$pair" "run $variant exited $exitval (signal $signal): $(cat "$work/logs/$pair-$variant.log")" ;;
  esac
done < <(tail -n +2 "$work/logs/joblog")
for pair in $(seq 1 "$pairs"); do
  dir="$work/pair-$pair"
  winner=$(matching_variant "$dir/out")
  if [ -z "$winner" ]; then
    fail "$pair" "the folder holds no one run's complete outputs: $(ls -A "$dir/out" 2>&1 | tr '\n' ' ')"
  elif [ "${status[$pair-$winner]:-}" != 0 ]; then
    fail "$pair" "the folder holds run $winner's outputs, but that run exited ${status[$pair-$winner]:-(not at all)}"
  fi
  left=$(ls -A "$dir" | grep -vx out || true)
  [ -z "$left" ] || fail "$pair" "left beside the folder: $(tr '\n' ' ' <<<"$left")"
done
echo "$pairs pairs, $((2 * pairs)) runs: ${#status[@]} in the job log, $zeros exited 0, $twos exited 2 with a message; $failures failures"
[ "${#status[@]}" = $((2 * pairs)) ] && [ "$failures" = 0 ]
