#pragma once
// The sections of report.html, each an HTML fragment: a heading, the chart(s) and a note on
// anything left out (downsampled rows, hosts or phases not drawn, data not recorded).

#include "report/report_activity.hpp"

#include <pagecache/run.hpp>

#include <string>

namespace pagecache::report {

/// Each host's memory over time, stacked: anonymous, cached clean, dirty, writeback, free (GB).
/// At most kMaxMemoryHosts hosts, each downsampled to at most kMaxMemoryPoints steps.
std::string memory_figures(const RunResult& result);
inline constexpr std::size_t kMaxMemoryHosts = 8;
inline constexpr std::size_t kMaxMemoryPoints = 1000;

/// A Gantt chart of the phases, a row per task, up to kMaxGanttTasks tasks; beyond, the mean
/// number of tasks reading, computing and writing over time, in at most kPhaseBuckets buckets.
std::string phase_figure(const RunResult& result);
inline constexpr std::size_t kMaxGanttTasks = 200;
inline constexpr std::size_t kPhaseBuckets = 1000;

/// The page cache contents per file after each I/O phase (the first kMaxCachePhases), the
/// kMaxCacheFiles largest files apart and the others together; or why they were not recorded.
std::string cache_figure(const RunResult& result);
inline constexpr std::size_t kMaxCachePhases = 100;
inline constexpr std::size_t kMaxCacheFiles = 7;

/// Bytes written back (by cause) and evicted per time bucket, and the throttling pauses; or a
/// note that they were not recorded.
std::string activity_figure(const ReportActivity& activity);

}  // namespace pagecache::report
