#!/usr/bin/env bash
# report.html opened in a real browser (headless Chromium) for four runs: the embedded default
# (the paper's Exp 1 at 100 GB), Exp 2 with 32 pipelines, Exp 2 with 10^4 pipelines, and a
# WfCommons workflow with long task and file names. The DOM Chromium builds must hold the charts
# the page promises, with their series and row counts; the largest page must stay under 5 MB; and
# opening a page must make no network request: Chromium's net log may hold its own background
# requests (initiator "not an origin"), never one from the page. A control page with an <img> on
# http:// shows that the net log check catches one. Every label is measured as drawn
# (report_labels_check.js, run in a copy of the page): whole or shortened with its full name in a
# <title>, inside the SVG, no two texts of a chart overlapping, no legend entry repeated; a
# control page with a clipped label and two overlapping ones shows that the check catches them.
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

# `check_labels NAME PAGE`: report_labels_check.js run in a copy of PAGE (the page itself has no
# script); its findings into $work/NAME.labels, its first line "labels=L shortened=S texts=T
# problems=P". Status 1 on any problem, or if the check wrote nothing.
check_labels() {
  local name=$1 page=$2
  { cat "$page"; echo '<script>'; cat "$source_dir/tests/apps/report_labels_check.js"; echo '</script>'; } >"$work/$name.check.html"
  browser --dump-dom "file://$work/$name.check.html" | sed -n '/<pre id="label-check">/,/<\/pre>/p' |
    sed -e 's/.*<pre id="label-check">//' -e 's/<\/pre>.*//' >"$work/$name.labels"
  grep -q '^labels=[0-9]* shortened=[0-9]* texts=[0-9]* problems=0$' "$work/$name.labels"
}

# `labels NAME KEY`: KEY's count in NAME's label check ("labels", "shortened", "texts").
labels() { sed -n "1s/.*\b$2=\([0-9]*\).*/\1/p" "$work/$1.labels"; }

# The control: a label starting left of the SVG, two overlapping ticks, a legend entry twice.
cat >"$work/control-labels.html" <<'HTML'
<!DOCTYPE html><html><body><svg class="chart" data-chart="control" width="300" height="100" viewBox="0 0 300 100" style="font-size:12px">
<g class="gantt-row"><text class="tick" x="20" y="20" text-anchor="end"><title>a long name</title>a long name</text></g>
<text class="tick" x="100" y="60">1000</text><text class="tick" x="110" y="60">2000</text>
<g class="legend-item"><title>f</title><rect fill="#000" fill-opacity="1"/><text x="200" y="20">f</text></g>
<g class="legend-item"><title>f</title><rect fill="#000" fill-opacity="1"/><text x="200" y="40">f</text></g></svg></body></html>
HTML
! check_labels control "$work/control-labels.html" || fail "the label check passed the control page"
for caught in 'starts left of x = 0' '"2000" overlaps "1000"' 'legend entry "f" is repeated'; do
  grep -q -F -- "$caught" "$work/control.labels" || fail "the label check missed the control's '$caught'"
done

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
  check_labels "$name" "$page" || fail "$name: labels: $(head -c 2000 "$work/$name.labels")"
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

# (d) A WfCommons workflow (Epigenomics, 41 tasks) on the Chameleon platform: task names up to
# 70 characters ("fast2bfq_fast2bfq_HEP2_MSP1_Digests_s_1_sequence_1_ID0000002"), files whose names
# differ only near their end. A Gantt row per task of timeline.csv, titled "app/task" in full; the
# long ones shortened (the check above measured them); the legend of cached files has 8 entries.
run wf-epigenomics "$source_dir/inputs/wfcommons/instances/epigenomics-chameleon-hep-1seq-100k-001.json" \
  --platform "$source_dir/platforms/wfcommons-chameleon.xml"
expect wf-epigenomics 'data-chart="gantt" data-series="3" data-rows="41"' 1
diff <(sed -n 's/^\([^,]*\),\([^,]*\),.*/\1\/\2/p' "$work/wf-epigenomics/timeline.csv" | sed 1d | sort -u) \
  <(grep -o '<g class="gantt-row"><text[^>]*><title>[^<]*</title>' "$work/wf-epigenomics.dom" | sed 's/.*<title>\(.*\)<\/title>/\1/' | sort) >/dev/null ||
  fail "wf-epigenomics: the Gantt rows' titles are not timeline.csv's app/task names, each once"
[ "$(labels wf-epigenomics shortened)" -gt 0 ] || fail "wf-epigenomics: no label was shortened: the check did not meet a long name"
expect wf-epigenomics '<g class="legend-item"' $((5 + 3 + 8 + 6))

echo "four reports checked in $(($(date +%s) - start)) s; $failures failures"
[ "$failures" = 0 ]
