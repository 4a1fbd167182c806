#pragma once
// The real fio on this machine, for `pcsim validate --here --fio`: one run of a job file as a
// child process, in a folder of its own that pcsim makes inside the user's and removes with
// everything fio wrote there. Each run starts as pcsim's does: the page cache dropped (as root)
// and the memory that freed reported to a virtual machine's host (cold_start.hpp); fio's
// invalidate=1 (its default) drops each job's files at open, which pcsim simulates too.

#include <cstdint>
#include <filesystem>
#include <string>

namespace pagecache::calibrate {

/// What one run of fio printed.
struct RealFio {
  std::string json;  ///< fio's JSON report (stdout from its first line that opens with '{')
  double seconds = 0.0;  ///< wall time of the run
  bool dropped_all_caches = false;  ///< the page cache dropped before it (as root)
  /// Before it, free page reporting: 1 settled (the freed memory reported), 0 still reporting
  /// after the wait's limit, -1 not counted here (no free page reporting).
  int reporting_settled = -1;
  /// Run in a memory cgroup: the most memory it used at once (bytes); -1 if none or unknown.
  std::int64_t peak_memory = -1;
};

class MemoryCgroup;

/// Runs `fio --output-format=json --timeout=T JOB` with its working directory a fresh folder
/// in `dir` (removed after), after the cache is dropped and free page reporting has settled
/// (waiting at most `settle_limit` seconds). `timeout_seconds` is fio's --timeout; a fio still running well
/// after it is killed. Throws pagecache::Error quoting fio's stderr if fio cannot start, fails
/// (non-zero exit), prints no JSON or is interrupted (SIGINT, SIGTERM: stop_requested()).
/// With `cgroup`, fio starts inside it (a shell joins it, then becomes fio).
RealFio run_real_fio(const std::filesystem::path& job, const std::filesystem::path& dir, int timeout_seconds, double settle_limit,
                     const std::string& fio = "fio", const MemoryCgroup* cgroup = nullptr);

}  // namespace pagecache::calibrate
