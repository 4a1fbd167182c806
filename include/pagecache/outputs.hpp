#pragma once
// Outputs: the files `pcsim run` writes, for a program that embeds the library to write the
// same, byte for byte. A run's folder holds timeline.csv (a row per phase), memory.csv (each
// host's memory over time), cache.csv (each file's cached bytes after every I/O phase),
// summary.json (the totals), timing.json (the simulator's own speed, the one file that
// differs between two runs of one scenario), report.html (the run drawn in one offline page)
// and, if asked for, trace.json (Chrome Trace Event format, for Perfetto). The folder is
// written beside its target and put in place whole: a failed run leaves nothing half-written,
// and only a folder pcsim made (marked by a `.pcsim-output` file) or an empty one is replaced.
// The README's table of outputs gives every column and key.
//
//   pagecache::RunOutputs outputs({.report = true, .trace = false});
//   pagecache::RunOptions options;
//   outputs.attach(options);                           // before the run
//   const pagecache::RunResult result = pagecache::run_scenario(scenario, options);
//   outputs.write("my-run", scenario, result);         // as `pcsim run --out my-run`

#include <pagecache/run.hpp>
#include <pagecache/scenario.hpp>

#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace pagecache {

/// What RunOutputs writes beside the CSV and JSON files.
struct OutputSettings {
  /// report.html.
  bool report = true;
  /// trace.json (`pcsim run` writes it with --trace or when the scenario says `trace = true`,
  /// Scenario::trace).
  bool trace = false;
  /// Past this size of trace events, trace.json keeps phases and memory counters only
  /// (RunOutputs::trace_truncated() says so): a trace of a huge run stays usable.
  std::size_t trace_max_bytes = std::size_t{1} << 30;
};

/// The outputs of one run: what report.html and trace.json need recorded during the run, then
/// every file written into a folder. `pcsim run` writes its outputs through this class.
class RunOutputs {
 public:
  explicit RunOutputs(OutputSettings settings = {});
  ~RunOutputs();
  RunOutputs(const RunOutputs&) = delete;
  RunOutputs& operator=(const RunOutputs&) = delete;

  /// Puts the recorders of report.html's activity chart and trace.json in
  /// `options.consumers` (none if neither file is wanted). Call it before the run; this object
  /// must outlive the run.
  void attach(RunOptions& options);

  /// Writes every output of `result`, a run of `scenario`, into the folder `dir` (made if
  /// absent, with the folders above it), as `pcsim run --out dir` does; cache.csv only if the
  /// run recorded the cache contents (RunOptions::cache_contents). The recorders' memory is
  /// freed as their files are written: call it once. Throws ConfigError if `dir` may not be
  /// replaced (it holds files pcsim did not write, is a file or a link, or is the current
  /// folder or one above it), Error if a file cannot be written. Returns warnings for a
  /// person, e.g. a replaced folder kept aside because someone wrote into it meanwhile.
  std::vector<std::string> write(const std::string& dir, const Scenario& scenario, const RunResult& result);

  /// report.html's text for `result`, a run of `scenario`, as write() writes it (e.g. to show
  /// it inline in a notebook). Any number of times, before write(); ConfigError if this object
  /// was made without OutputSettings::report.
  std::string report_html(const Scenario& scenario, const RunResult& result) const;
  /// Whether trace.json dropped transfers, flushes, evictions and pauses past
  /// OutputSettings::trace_max_bytes (known once write() has run).
  bool trace_truncated() const noexcept { return trace_truncated_; }
  /// Whether write() writes trace.json.
  bool writes_trace() const noexcept;

 private:
  struct Recorders;
  OutputSettings settings_;
  std::unique_ptr<Recorders> recorders_;
  bool trace_truncated_ = false;
  bool written_ = false;
};

/// The check `pcsim run` makes before simulating: throws ConfigError, naming the folder and
/// why, if RunOutputs::write could not replace `dir` now (what is there is not pcsim's, or no
/// folder can be made beside it), or if `dir` holds `scenario_file` (the scenario would be
/// deleted with the folder; empty: no scenario file).
void check_output_folder(const std::string& dir, const std::string& scenario_file = {});

/// The files one by one. The CSV files are RFC 4180: a name holding a comma, a quote, CR or
/// LF, or starting or ending with a space is quoted; one starting with =, +, -, @, TAB or CR
/// gets a ' before it, so that no spreadsheet runs it as a formula. They are written as they
/// are formatted (never whole in memory), by the rule of every file pcsim writes: a regular
/// file (or none yet) is written beside `path` and renamed over it whole, a link's regular
/// target likewise (the link stays), a character device or FIFO is written through; a folder,
/// a link to nothing, a socket or a missing folder is a ConfigError. Error if it cannot be
/// written.
void write_timeline_csv(const std::filesystem::path& path, const RunResult& result);
void write_memory_csv(const std::filesystem::path& path, const RunResult& result);
void write_cache_csv(const std::filesystem::path& path, const RunResult& result);
/// summary.json: the run's results, the same for the same scenario, byte for byte.
std::string summary_json(const Scenario& scenario, const RunResult& result);
/// timing.json: the simulator's own wall time and events per second.
std::string timing_json(const RunResult& result);
/// Where the cache contents are ("cache.csv") or why they were not recorded.
std::string cache_contents_note(const RunResult& result);
/// The summary `pcsim run` prints: a small table per application (at most eight) and the
/// totals, names shown with control characters escaped.
std::string readable_summary(const Scenario& scenario, const RunResult& result);

}  // namespace pagecache
