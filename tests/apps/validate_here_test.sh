#!/usr/bin/env bash
# pcsim validate --here, run as a user runs it, at a tiny scale (--quick: two tiny cases, one
# repetition, a quick calibration): (a) it runs the real pipelines, prints the error table,
# keeps the measurements in a new folder and leaves --dir as it found it; (b) --from scores
# the kept folder again, without I/O, to the same table; (c) an existing --out, a missing
# --dir, a folder that is not one of its own and a kept folder whose phases are gone are
# refused with exit 2 and nothing written; (d) when run by root, the same as the ordinary user nobody, which says what it could not
# do. The committed measurements of the development machine are scored again too. No error
# is judged: the figures measure this machine.
#
#   validate_here_test.sh PCSIM_BINARY SOURCE_DIR
set -euo pipefail
pcsim=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
source_dir=$2
work=$(mktemp -d "${TMPDIR:-/tmp}/pcsim-here.XXXXXX")
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# (a) A tiny validation.
mkdir "$work/dir"
echo "mine" >"$work/dir/keep.txt"
"$pcsim" validate --here --quick --dir "$work/dir" --out "$work/results" >"$work/out.txt" 2>&1 ||
  { cat "$work/out.txt"; fail "(a): validate --here failed"; }
for f in platform.toml runs.csv phases.csv memory.csv report.txt; do
  [ -s "$work/results/$f" ] || fail "(a): no $f kept"
done
grep -q "^exp1-quick: 1 pipeline of 3 tasks" "$work/out.txt" || fail "(a): no exp1-quick line: $(head -3 "$work/out.txt")"
grep -q "^exp2-quick-2: 2 pipelines of 3 tasks" "$work/out.txt" || fail "(a): no exp2-quick-2 line"
grep -q "^over 2 cases: mean makespan error" "$work/out.txt" || fail "(a): no summary line"
[ "$(grep -c '^exp1-quick,' "$work/results/phases.csv")" = 9 ] || fail "(a): exp1-quick should have 9 phases (3 tasks x read, compute, write)"
[ "$(grep -c ',read,' "$work/results/phases.csv")" = 9 ] || fail "(a): 9 reads expected (3 + 2 x 3)"
[ "$(ls -A "$work/dir")" = keep.txt ] || fail "(a): --dir was left with: $(ls -A "$work/dir" | tr '\n' ' ')"

# (b) Scored again from the folder: the same table, no I/O.
"$pcsim" validate --from "$work/results" >"$work/again.txt" || fail "(b): --from failed"
cmp -s "$work/again.txt" "$work/results/report.txt" || fail "(b): --from gives another table: $(diff "$work/again.txt" "$work/results/report.txt" | head -5)"

# (c) Refused, exit 2, nothing written.
expect_refused() {
  local what=$1 pattern=$2
  shift 2
  local status=0
  "$pcsim" validate "$@" >"$work/refused.txt" 2>&1 || status=$?
  [ "$status" = 2 ] || fail "($what): exit $status, expected 2: $(cat "$work/refused.txt")"
  grep -q -- "$pattern" "$work/refused.txt" || fail "($what): the message does not say '$pattern': $(cat "$work/refused.txt")"
}
expect_refused "existing --out" "exists" --here --quick --dir "$work/dir" --out "$work/results"
expect_refused "no --dir" "needs --dir" --here --quick --out "$work/new"
expect_refused "--dir missing" "not a folder" --here --quick --dir "$work/nowhere" --out "$work/new"
expect_refused "--from elsewhere" "cannot read" --from "$work/dir"
cp -r "$work/results" "$work/broken"
head -1 "$work/results/phases.csv" >"$work/broken/phases.csv"
expect_refused "--from without phases" "runs.csv:2: case exp1-quick repetition 1: no read phase of pipeline 1, task 1 in phases.csv" --from "$work/broken"
[ ! -e "$work/new" ] || fail "(c): --out was made"
cmp -s "$work/again.txt" "$work/results/report.txt" || fail "(c): the kept measurements changed"

# (d) As an ordinary user, when this is root.
if [ "$(id -u)" = 0 ] && id nobody >/dev/null 2>&1; then
  mkdir "$work/nobody"
  chmod 755 "$work"
  chown nobody "$work/nobody"
  (cd "$work/nobody" && setpriv --reuid=nobody --regid="$(id -g nobody)" --clear-groups \
    "$pcsim" validate --here --quick --dir "$work/nobody" --out "$work/nobody/results") >"$work/nobody.txt" 2>&1 ||
    { cat "$work/nobody.txt"; fail "(d): validate --here as nobody failed"; }
  grep -q "note: not root" "$work/nobody.txt" || fail "(d): as nobody it does not say what it could not do"
  [ "$(ls -A "$work/nobody")" = results ] || fail "(d): nobody's folder was left with: $(ls -A "$work/nobody" | tr '\n' ' ')"
fi

# The development machine's measurements, committed: scored again by this pcsim.
for kept in "$source_dir"/validation/here/*/; do
  [ -f "$kept/runs.csv" ] || continue
  "$pcsim" validate --from "$kept" >"$work/kept.txt" 2>&1 || fail "kept measurements $kept: $(tail -3 "$work/kept.txt")"
  grep -q "^over 5 cases" "$work/kept.txt" || fail "kept measurements $kept: not five cases scored"
done

[ "$failures" = 0 ] && echo "validate --here: all checks passed"
exit "$failures"
