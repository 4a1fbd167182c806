#pragma once
// Writing a run's outputs: timeline.csv, memory.csv, cache.csv, summary.json, timing.json,
// report.html (and trace.json) in one folder, marked as pcsim's and put in place whole
// (output_folder.hpp), so that a failed run never leaves a half-written result. The files one
// by one, and RunOutputs, which records and writes them all, are public (pagecache/outputs.hpp).

#include "report/report_activity.hpp"

#include <pagecache/outputs.hpp>
#include <pagecache/run.hpp>
#include <pagecache/scenario.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace pagecache::report {

/// An output made by one of the run's consumers (trace.json); its name is one of kOutputNames.
struct NamedOutput {
  std::string name;
  std::string text;
};

struct OutputOptions {
  /// Write report.html.
  bool report = true;
  /// The ReportActivity attached to the run, drawn in report.html (nullptr: the page says it
  /// was not recorded).
  const ReportActivity* activity = nullptr;
  std::vector<NamedOutput> more;
};

/// Writes every output into `dir`, replacing it if it is pcsim's (output_rules.hpp); cache.csv
/// only if the cache contents were recorded. Throws ConfigError if `dir` may not be replaced,
/// Error if a file cannot be written or `options.more` names a file pcsim does not write.
/// Returns warnings for the user (see OutputFolder::commit).
std::vector<std::string> write_outputs(const std::string& dir, const Scenario& scenario, const RunResult& result,
                                       const OutputOptions& options = {});

}  // namespace pagecache::report
