#!/usr/bin/env bash
# report.html opened in a real browser (headless Chromium) for three runs: the embedded default
# (the paper's Exp 1 at 100 GB), Exp 2 with 32 pipelines, and Exp 2 with 10^4 pipelines. The DOM
# Chromium builds must hold the charts the page promises, with their series and row counts; the
# largest page must stay under 5 MB; and opening a page must make no network request: Chromium's
# net log may hold its own background requests (initiator "not an origin"), never one from the
# page. A control page with an <img> on http:// shows that the net log check catches one.
# Screenshots are kept in the build folder (report-<name>.png).
#
#   report_browser_test.sh PCSIM_BINARY SOURCE_DIR BUILD_DIR
set -euo pipefail
pcsim=$1
source_dir=$2
build_dir=$3
command -v chromium >/dev/null || { echo "chromium is missing (scripts/install-deps installs it)"; exit 1; }
work=$(mktemp -d "${TMPDIR:-/tmp}/pcsim-report-browser.XXXXXX")
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# Chromium with a profile of its own in the scratch folder, killed if it hangs.
browser() {
  timeout -k 5 120 chromium --headless --no-sandbox --disable-gpu --disable-background-networking --no-first-run \
    --user-data-dir="$work/profile" "$@" 2>>"$work/chromium.log"
}

# Opens `page`: its DOM into $work/NAME.dom, its net log into $work/NAME.netlog.
open_page() {
  local name=$1 page=$2
  browser --log-net-log="$work/$name.netlog" --dump-dom "file://$page" >"$work/$name.dom"
}

# Requests the page made to http, https, ws or wss (Chromium's own have no origin).
page_requests() {
  grep -E '"url":"(https?|wss?)://' "$1" | grep '"initiator"' | grep -v '"initiator":"not an origin"' || true
}

# `expect NAME TEXT COUNT`: TEXT occurs COUNT times in NAME's DOM.
expect() {
  local found
  found=$({ grep -o -F -- "$2" "$work/$1.dom" || true; } | wc -l)
  [ "$found" = "$3" ] || fail "$1: '$2' found $found times, expected $3"
}

# The control: the check sees a request the page makes.
printf '<!DOCTYPE html><html><body><img src="http://127.0.0.1:9/pixel.png"></body></html>\n' >"$work/control.html"
open_page control "$work/control.html"
[ -n "$(page_requests "$work/control.netlog")" ] || fail "the net log check missed the control page's request"

start=$(date +%s)
run() {
  local name=$1
  shift
  "$pcsim" run "$@" --out "$work/$name" --quiet
  local page="$work/$name/report.html"
  open_page "$name" "$page"
  browser --hide-scrollbars --window-size=1280,2400 --screenshot="$build_dir/report-$name.png" "file://$page" >/dev/null
  [ -s "$build_dir/report-$name.png" ] || fail "$name: no screenshot"
  local requests
  requests=$(page_requests "$work/$name.netlog")
  [ -z "$requests" ] || fail "$name: the page made requests: $requests"
  # Nothing the page could fetch: no src or href attribute, no url() in its style, no script.
  if grep -n -E '(src|href)=|url\(|@import|<script' "$page" >/dev/null; then fail "$name: the page refers to something outside it"; fi
  expect "$name" '<svg class="chart"' "$(grep -o '<svg class="chart"' "$page" | wc -l)"
  echo "$name: report.html $(stat -c %s "$page") bytes"
}

# (a) Exp 1 at 100 GB: one host, one pipeline of three tasks, four files, six I/O phases.
run exp1
expect exp1 'data-chart="memory" data-series="5"' 1
expect exp1 'data-chart="gantt" data-series="3" data-rows="3"' 1
expect exp1 '<g class="gantt-row">' 3
expect exp1 'data-chart="cache" data-series="4" data-rows="6"' 1
expect exp1 'data-chart="activity" data-series="6"' 1
expect exp1 'data-chart="phases"' 0

# (b) Exp 2, 32 pipelines of three tasks: 96 Gantt rows; 128 files, so 7 apart and the others
# together; 192 I/O phases, of which the first 100 are drawn.
run exp2-32 "$source_dir/scenarios/paper/exp2.toml" --set pipelines.count=32
expect exp2-32 'data-chart="gantt" data-series="3" data-rows="96"' 1
expect exp2-32 '<g class="gantt-row">' 96
expect exp2-32 'data-chart="cache" data-series="8" data-rows="100"' 1
expect exp2-32 'I/O phases: the first 100 are drawn' 1
expect exp2-32 'data-chart="activity" data-series="6"' 1

# (c) Exp 2, 10^4 pipelines (10 MB files: 3 GB ones would not fit on the disk): no Gantt chart,
# the tasks in each phase over time instead; the page under 5 MB.
run exp2-10000 "$source_dir/scenarios/paper/exp2.toml" --set pipelines.count=10000 --set 'pipelines.file_size="10 MB"' --no-cache-contents
expect exp2-10000 'data-chart="gantt"' 0
expect exp2-10000 'data-chart="phases" data-series="3" data-rows="1000"' 1
expect exp2-10000 '30000 tasks, more than the 200' 1
size=$(stat -c %s "$work/exp2-10000/report.html")
[ "$size" -lt 5000000 ] || fail "exp2-10000: report.html is $size bytes, 5 MB or more"

echo "three reports checked in $(($(date +%s) - start)) s; $failures failures"
[ "$failures" = 0 ]
