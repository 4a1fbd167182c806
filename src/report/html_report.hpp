#pragma once
// report.html: a run drawn for a person, in one self-contained file (inline CSS and SVG, no
// script, nothing fetched: it opens offline from file://). A summary table, each host's memory
// over time, the phases of the tasks, the cache contents after each I/O phase, and the
// writeback and eviction activity. Byte-identical for the same run: no wall time, no date.

#include "report/report_activity.hpp"

#include <pagecache/run.hpp>
#include <pagecache/scenario.hpp>

#include <string>

namespace pagecache::report {

/// The page for `result`, a run of `scenario`; `activity` is the ReportActivity attached to the
/// run (one never attached, recorded() false, makes the activity section say so). Every chart
/// is an `<svg class="chart" data-chart=... data-series=... data-rows=...>` (see chart/frame.hpp).
std::string report_html(const Scenario& scenario, const RunResult& result, const ReportActivity& activity);

}  // namespace pagecache::report
