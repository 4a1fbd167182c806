#pragma once
// `pcsim validate --here --fio` scored: each job of each kept job file simulated on the kept
// platform (its copy run as `pcsim run JOB.fio --platform platform.toml` runs it) and each
// direction a job did I/O in compared with fio's bandwidth: the repetitions' median, their
// spread ((max - min) / median), pcsim's, the error pcsim / median - 1, and a verdict: within
// if |error| <= max(15 %, spread).

#include "validate/fio_kept.hpp"

#include <pagecache/run.hpp>
#include <pagecache/scenario.hpp>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace pagecache::validate {

/// A job file simulated on a platform file.
struct FioSimulation {
  Scenario scenario;
  RunResult result;
};

/// Loads `job` on `platform` as `pcsim run` does (a job file pcsim refuses throws its
/// ConfigError) and simulates it; `memory_max` > 0: in a memory cgroup of that limit, as
/// `--set fio.memory_max=BYTES` runs it.
FioSimulation simulate_fio(const std::filesystem::path& job, const std::filesystem::path& platform, std::int64_t memory_max = 0);

/// One job's one direction.
struct FioScore {
  std::string job_file, job, direction;  ///< direction: "read" or "write"
  std::vector<double> measured;  ///< fio's bw_bytes per repetition (B/s)
  double median = 0.0, spread = 0.0;  ///< of measured; spread as a fraction
  double pcsim = 0.0;  ///< B/s
  double error = 0.0;  ///< pcsim / median - 1 (NaN if the median is 0)
  bool within = false;
};

/// The scores of `runs`, kept in `folder` (its platform.toml and job file copies). Throws
/// ConfigError naming a report whose jobs are not pcsim's jobs of its job file.
std::vector<FioScore> score_fio(const std::filesystem::path& folder, const std::vector<FioJobFileRuns>& runs);

/// The printable table.
std::string fio_scores_table(const std::vector<FioScore>& scores);
/// fio-scores.json's text: {"tolerance": 0.15, "scores": [{job_file, job, direction,
/// measured_bytes_per_second: [...], median_bytes_per_second, spread, pcsim_bytes_per_second,
/// error (null if the median is 0), verdict}]}.
std::string fio_scores_json(const std::vector<FioScore>& scores);

}  // namespace pagecache::validate
