#pragma once
// The measurements `validate --here --fio` keeps in its --out folder, read back for `validate
// --from`: platform.toml, each job file's copy, each repetition's fio JSON report
// (fio-STEM-REP.json) and the manifest fio-runs.csv listing them (job_file, repetition,
// json_file, memory_max: the memory cgroup's limit or 0, peak_memory: its peak use or -1; an
// older manifest without the last two ran without a limit). Read strictly: a missing or
// malformed file is a ConfigError naming it.

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace pagecache::validate {

/// One direction of one job as fio's JSON reports it.
struct FioMeasuredDirection {
  std::int64_t io_bytes = 0;
  std::int64_t bw_bytes = 0;    ///< B/s
  std::int64_t runtime_ms = 0;
};

struct FioMeasuredJob {
  std::string name;  ///< fio's jobname
  FioMeasuredDirection read, write;
};

/// One run of fio on one job file.
struct FioRepetition {
  int repetition = 0;     ///< from 1
  std::string json_file;  ///< its report's name in the folder
  std::vector<FioMeasuredJob> jobs;  ///< in fio's order
  std::int64_t peak_memory = -1;  ///< in its memory cgroup (bytes); -1: none or unknown
};

/// A job file and its repetitions.
struct FioJobFileRuns {
  std::string job_file;  ///< its copy's name in the folder
  std::vector<FioRepetition> repetitions;
  std::int64_t memory_max = 0;  ///< the memory cgroup fio ran in (bytes), simulated too; 0: none
};

/// The manifest's name: its presence makes a folder one of fio measurements.
inline constexpr const char* kFioManifest = "fio-runs.csv";

/// fio's JSON report `json` (of file `file`, for messages): per job in order, its jobname and
/// the io_bytes, bw_bytes and runtime of read and write. Throws ConfigError naming the file.
std::vector<FioMeasuredJob> parse_fio_report(std::string_view json, const std::string& file);

/// The manifest's text for `runs`.
std::string fio_manifest(const std::vector<FioJobFileRuns>& runs);

/// Whether `folder` holds fio measurements (a manifest).
bool is_fio_folder(const std::filesystem::path& folder);

/// The manifest of `folder` and every report it names, each job file's repetitions in order,
/// every job file copy present. Throws ConfigError naming the file at fault.
std::vector<FioJobFileRuns> load_fio_runs(const std::filesystem::path& folder);

}  // namespace pagecache::validate
