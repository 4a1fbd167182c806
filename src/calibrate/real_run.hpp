#pragma once
// Real pipelines on this machine, for `pcsim validate --here`: the paper's experiments done
// for real, with real files, read(2) and write(2) in chunks and a CPU-bound computation, every
// phase's start and end recorded, and /proc/meminfo sampled throughout.
//
// A pipeline is what pcsim's [pipelines] simulates: task k reads file k whole into a new
// buffer, computes, writes file k + 1 from it, and frees the buffer; the pipelines run at
// once, one thread each.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace pagecache::calibrate {

struct RealCase {
  std::string name;
  int pipelines = 1;
  int tasks = 3;
  std::int64_t file_size = 0;
  double compute = 0.0;  ///< CPU seconds per task (the thread's own CPU time)
  std::int64_t chunk = 100'000'000;
};

struct RealPhase {
  int pipeline = 0;  ///< from 1
  int task = 0;      ///< from 1
  std::string phase;  ///< read, compute, write
  double start = 0.0;  ///< seconds since the run started
  double end = 0.0;
};

/// /proc/meminfo at a time of the run.
struct MemorySample {
  double time = 0.0;
  std::int64_t free = 0, cached = 0, dirty = 0, writeback = 0;
};

struct RealRun {
  RealCase spec;
  int repetition = 0;  ///< from 1
  std::vector<RealPhase> phases;
  std::vector<MemorySample> memory;
  double makespan = 0.0;          ///< the end of the last phase
  std::int64_t memory_total = 0;  ///< MemTotal
  std::int64_t in_use_at_start = 0;  ///< MemTotal - MemAvailable when it started
  std::int64_t free_at_start = 0;    ///< MemFree when it started
  bool dropped_all_caches = false;   ///< root dropped the whole page cache first
  // What else happened on the machine while it ran (-1: not recorded, an older folder).
  double others_busy_cores = -1.0;  ///< CPUs busy outside this process (other load, kernel threads)
  double steal_pct = -1.0;          ///< of the CPUs' time, taken by the hypervisor
  std::int64_t reported = -1;       ///< bytes of free memory reported to a VM's host
  /// Bytes of the free memory at the start not yet reported to a VM's host (free page
  /// reporting): 0 once the run waited for the kernel to report what was freed before it; -1:
  /// not known (an older folder: its inputs, dropped just before, are taken).
  std::int64_t warm_at_start = -1;
};

/// Runs `spec` in `dir` (its files made there first and removed after): as root, after
/// dropping the whole page cache (sync; drop_caches); otherwise after dropping its own input
/// files' pages. Where the machine reports free pages to its host, it then waits (at most
/// `settle_limit` seconds) until the kernel has reported what was freed, so that the run
/// starts with all free memory cold, as pcsim then starts it. `sample_interval`: seconds
/// between memory samples.
RealRun run_real(const RealCase& spec, const std::filesystem::path& dir, int repetition, double sample_interval, double settle_limit = 40.0);

}  // namespace pagecache::calibrate
