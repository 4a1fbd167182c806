#!/usr/bin/env bash
# scripts/check-outputs, the before/after check of restructurings, on one build twice: the
# manifest holds every case (down to validate's last file) and is the same the second time, so
# the script cannot rot and the outputs it digests are deterministic.
#   check_outputs_test.sh PCSIM_BINARY SOURCE_DIR
set -euo pipefail
manifest=$(mktemp "${TMPDIR:-/tmp}/pcsim-manifest.XXXXXX")
trap 'rm -f "$manifest"' EXIT
"$2/scripts/check-outputs" "$1" >"$manifest"
grep -q '^default/paper summary.json ' "$manifest"
grep -q '^validate/linux v.html ' "$manifest"
"$2/scripts/check-outputs" "$1" --against "$manifest"
