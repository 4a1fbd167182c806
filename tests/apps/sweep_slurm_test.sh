#!/usr/bin/env bash
# pcsim sweep on a real Slurm: a one-node cluster started for the test (munged, slurmctld,
# slurmd; tests/support/slurm_cluster.sh), the sbatch script `pcsim sweep slurm` prints for the
# 128 runs of the paper's Exp 2 in a four-task job array, submitted and waited for; its merged
# results.csv must be the one a single process gives, but for the wall times. The daemons
# the test started are stopped whatever happens.
#
#   sweep_slurm_test.sh PCSIM_BINARY SOURCE_DIR
set -euo pipefail
pcsim=$1
source_dir=$2
here=$(cd "$(dirname "$0")" && pwd)
. "$here/sweep_exp2.sh"
cluster_kit=$here/../support/slurm_cluster.sh
# Short: the cluster's munge socket lives under it (a unix socket path has at most 107 bytes).
work=$(mktemp -d /tmp/pcsim-slurm.XXXXXX)
mkdir "$work/cluster"
trap '"$cluster_kit" stop "$work/cluster" >/dev/null || true; rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

"$cluster_kit" start "$work/cluster" >/dev/null
export SLURM_CONF=$work/cluster/slurm.conf
exp2=$(exp2_sweep_file "$source_dir")

"$pcsim" sweep run "$exp2" --out "$work/one" --jobs 2 --quiet
"$pcsim" sweep merge "$work/one" >/dev/null

"$pcsim" sweep slurm "$exp2" --shards 4 --out "$work/slurm" --time 00:10:00 >"$work/exp2.sbatch"
grep -q '^#SBATCH --array=0-3$' "$work/exp2.sbatch" || fail "the script asks for no 4-task array: $(cat "$work/exp2.sbatch")"
start=$(date +%s)
# --wait: back when every array task has ended, with the highest exit code among them.
timeout 300 sbatch --wait --quiet "$work/exp2.sbatch" || fail "the array job failed: $(cat "$work"/slurm/slurm-*.out 2>/dev/null)"
echo "the job array took $(($(date +%s) - start)) s"
for i in 0 1 2 3; do
  [ -s "$work/slurm/results-$i-of-4.jsonl" ] || fail "array task $i wrote no results-$i-of-4.jsonl"
done
"$pcsim" sweep merge "$work/slurm" >/dev/null || fail "merge refused the array's results"
[ "$(wc -l <"$work/slurm/results.csv")" = 129 ] || fail "$(wc -l <"$work/slurm/results.csv") lines, expected a header and 128 runs"
cmp <(without_wall_times "$work/one/results.csv") <(without_wall_times "$work/slurm/results.csv") || fail "results.csv differs from one process's"

echo "slurm sweep test: $failures failures"
[ "$failures" = 0 ]
