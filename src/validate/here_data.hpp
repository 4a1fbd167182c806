#pragma once
// The measurements `validate --here` keeps (here_files), read back for `validate --from` as
// strictly as a scenario: each file's columns present, every number finite, not negative
// where that makes no sense and within what pcsim takes (durations up to 10^9 s, sizes up to
// 1 EiB); then across the files: every phase and sample of a run listed in runs.csv, each
// once, every run with all its phases and a memory sample. A fault is a ConfigError naming the
// file, the line and the column. load_here (here.hpp) reads a folder with these.

#include "validate/here.hpp"

#include <string>
#include <string_view>
#include <vector>

namespace pagecache::validate {

/// A row of runs.csv.
struct KeptRun {
  int line = 0;
  calibrate::RealRun run;  ///< without phases and memory
};

/// A row of phases.csv or of memory.csv: the run it belongs to, and what it holds.
template <class T>
struct KeptRow {
  int line = 0;
  std::string case_name;
  int repetition = 0;
  T value;
};

std::vector<KeptRun> read_kept_runs(std::string_view text, const std::string& file);
std::vector<KeptRow<calibrate::RealPhase>> read_kept_phases(std::string_view text, const std::string& file);
std::vector<KeptRow<calibrate::MemorySample>> read_kept_memory(std::string_view text, const std::string& file);

/// The files' texts, and their names for messages.
struct KeptTexts {
  std::string platform_toml;
  std::string runs, phases, memory;
  std::string runs_file = "runs.csv", phases_file = "phases.csv", memory_file = "memory.csv";
};

/// The measurements, each file read as above and the three checked against each other.
HereMeasurements parse_here(const KeptTexts& texts);

}  // namespace pagecache::validate
