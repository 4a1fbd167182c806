#pragma once
// The real fio on this machine, for `pcsim validate --here --fio`: one run of a job file as a
// child process, in a folder of its own that pcsim makes inside the user's and removes with
// everything fio wrote there. Nothing is dropped from the cache first: fio's invalidate=1 (its
// default) drops each job's files at open, which is what pcsim simulates.

#include <filesystem>
#include <string>

namespace pagecache::calibrate {

/// What one run of fio printed.
struct RealFio {
  std::string json;  ///< fio's JSON report (stdout from its first line that opens with '{')
  double seconds = 0.0;  ///< wall time of the run
};

/// Runs `fio --output-format=json --timeout=T JOB` with its working directory a fresh folder
/// in `dir` (removed after). `timeout_seconds` is fio's --timeout; a fio still running well
/// after it is killed. Throws pagecache::Error quoting fio's stderr if fio cannot start, fails
/// (non-zero exit), prints no JSON or is interrupted (SIGINT, SIGTERM: stop_requested()).
RealFio run_real_fio(const std::filesystem::path& job, const std::filesystem::path& dir, int timeout_seconds,
                     const std::string& fio = "fio");

}  // namespace pagecache::calibrate
