#pragma once
// Writing a run's outputs: timeline.csv, memory.csv, cache.csv, summary.json, timing.json,
// report.html (and trace.json) in one folder, marked as pcsim's and put in place whole (output_folder.hpp), so that a failed
// run never leaves a half-written result. Also the readable summary printed to stdout.

#include "report/report_activity.hpp"

#include <pagecache/run.hpp>
#include <pagecache/scenario.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace pagecache::report {

/// An output made by one of the run's consumers (trace.json); its name is one of kOutputNames.
struct OutputFile {
  std::string name;
  std::string text;
};

struct OutputOptions {
  /// Write report.html.
  bool report = true;
  /// The ReportActivity attached to the run, drawn in report.html (nullptr: the page says it
  /// was not recorded).
  const ReportActivity* activity = nullptr;
  std::vector<OutputFile> more;
};

/// Writes every output into `dir`, replacing it if it is pcsim's (output_rules.hpp); cache.csv
/// only if the cache contents were recorded. Throws ConfigError if `dir` may not be replaced,
/// Error if a file cannot be written or `options.more` names a file pcsim does not write.
/// Returns warnings for the user (see OutputFolder::commit).
std::vector<std::string> write_outputs(const std::string& dir, const Scenario& scenario, const RunResult& result,
                                       const OutputOptions& options = {});

/// The CSV files, each written to `path` as it is formatted (see outputs.cpp), their text
/// fields quoted and guarded against formulas as csv_field.hpp says. Throw Error if the file
/// cannot be written.
void write_timeline_csv(const std::filesystem::path& path, const RunResult& result);
void write_memory_csv(const std::filesystem::path& path, const RunResult& result);
void write_cache_csv(const std::filesystem::path& path, const RunResult& result);
/// The run's results: the same for the same scenario, byte for byte.
std::string summary_json(const Scenario& scenario, const RunResult& result);
/// The simulator's own speed (wall time, events per second): the one output that varies from
/// run to run, kept out of summary.json so that the others are byte-identical.
std::string timing_json(const RunResult& result);
/// Where the cache contents are ("cache.csv") or why they were not recorded.
std::string cache_contents_note(const RunResult& result);

/// A small table per application and the totals, for a terminal (names as text::printable()).
std::string readable_summary(const Scenario& scenario, const RunResult& result);

}  // namespace pagecache::report
