#!/usr/bin/env bash
# scripts/bench-user on each shape's smallest size, so that the harness of the user's command
# cannot rot: every run counted events and chunk operations, and wrote its report. No timing
# is checked: the figures measure the machine.
#   bench_user_test.sh PCSIM_BINARY SOURCE_DIR
set -euo pipefail
scratch=$(mktemp -d "${TMPDIR:-/tmp}/pcsim-bench-user-test.XXXXXX")
trap 'rm -rf "$scratch"' EXIT
"$2/scripts/bench-user" --pcsim "$1" --smallest --scratch "$scratch/runs" >"$scratch/out.txt"
cat "$scratch/out.txt"
python3 - "$scratch" <<'PY'
import json, os, sys
scratch = sys.argv[1]
lines = [json.loads(l) for l in open(os.path.join(scratch, "out.txt")) if l.startswith("{")]
shapes = {r["shape"] for r in lines}
expected = {"exp2-paper", "exp2-linux", "exp2-numa", "writers", "cluster", "dag"}
assert shapes == expected, f"shapes {sorted(shapes)}, expected {sorted(expected)}"
for r in lines:
    label = f"{r['shape']}-{r['n']}"
    assert r["events"] > 0 and r["chunk_operations"] > 0, f"{label}: {r}"
    for name in ("report.html", "summary.json", "timeline.csv", "memory.csv"):
        path = os.path.join(scratch, "runs", label, name)
        assert os.path.getsize(path) > 0, f"{path} missing or empty"
rows = [l for l in open(os.path.join(scratch, "out.txt")) if l.startswith("| ") and "---" not in l]
assert len(rows) == len(lines) + 1, f"{len(rows)} table lines for {len(lines)} runs"
print(f"bench_user_test: {len(lines)} runs, each with events and its report")
PY
