#pragma once
// validation/paper/'s files (its README says what each holds), read whole and checked before
// anything is simulated: the columns `pcsim validate` uses present, every number finite, not
// negative where that makes no sense, within what pcsim itself takes (durations up to 10^9 s,
// sizes up to 1 EiB), the real durations above 0 (errors are relative to them), each phase
// once. A fault is a ConfigError naming the file, the line and the column.

#include <string>
#include <string_view>
#include <vector>

namespace pagecache::validate {

/// A row of exp1_{real,wrench_cache}_phase_times.csv.
struct PhaseTime {
  int line = 0;
  int size_gb = 0;
  int task = 0;
  std::string phase;  ///< read, compute, write
  double end_s = 0.0;
  double duration_s = 0.0;
};

/// A row of exp1_real_memory_profile.csv.
struct MemoryProfileRow {
  int line = 0;
  int size_gb = 0;
  double time_s = 0.0;  ///< may be negative: sampled before the first read
  double cached_mb = 0.0, dirty_mb = 0.0, shmem_mb = 0.0;
};

/// A row of exp1_real_cache_contents.csv.
struct CachedFileRow {
  int line = 0;
  int size_gb = 0;
  std::string after_task;  ///< a task number, as the simulated task is named
  std::string after_phase;
  std::string file;
  double cached_gb = 0.0;
};

/// A row of exp{2,3}_{real,wrench_cache}_phase_times.csv.
struct ConcurrentPhase {
  int line = 0;
  int repetition = 0;  ///< 0 in WRENCH-cache's files, which have one
  int n = 0;           ///< n_pipelines
  std::string phase;   ///< read, compute, write
  double duration_s = 0.0;
};

template <class Row>
struct DataFile {
  std::string file;  ///< as named in messages
  std::vector<Row> rows;
};

/// Each file read from its text; `real`: a measurement (durations of reads and writes above 0),
/// else WRENCH-cache's output.
DataFile<PhaseTime> read_exp1_phase_times(std::string_view text, const std::string& file, bool real);
DataFile<MemoryProfileRow> read_exp1_memory_profile(std::string_view text, const std::string& file);
DataFile<CachedFileRow> read_exp1_cache_contents(std::string_view text, const std::string& file);
DataFile<ConcurrentPhase> read_concurrent_phase_times(std::string_view text, const std::string& file, bool real);

/// What `pcsim validate` reads of the folder.
struct PaperData {
  DataFile<PhaseTime> exp1_real, exp1_wrench;
  DataFile<MemoryProfileRow> exp1_memory;
  DataFile<CachedFileRow> exp1_cache;
  DataFile<ConcurrentPhase> exp2_real, exp2_wrench, exp3_real, exp3_wrench;
};

/// Every file of `dir`, each named `dir`/NAME in messages.
PaperData read_paper_data(const std::string& dir);

}  // namespace pagecache::validate
