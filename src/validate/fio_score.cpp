#include "validate/fio_score.hpp"

#include "report/fio_json.hpp"
#include "text/json_string.hpp"

#include <pagecache/error.hpp>
#include <pagecache/scenario_file.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace pagecache::validate {

namespace {

namespace fs = std::filesystem;

constexpr double kTolerance = 0.15;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n == 0 ? 0.0 : n % 2 == 1 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2.0;
}

FioScore score(const std::string& job_file, const std::string& job, const char* direction, std::vector<double> measured, double pcsim) {
  FioScore s{job_file, job, direction, std::move(measured)};
  s.median = median(s.measured);
  const auto [lo, hi] = std::minmax_element(s.measured.begin(), s.measured.end());
  s.spread = s.median > 0.0 ? (*hi - *lo) / s.median : 0.0;
  s.pcsim = pcsim;
  s.error = s.median > 0.0 ? pcsim / s.median - 1.0 : std::numeric_limits<double>::quiet_NaN();
  s.within = std::abs(s.error) <= std::max(kTolerance, s.spread);  // false for NaN
  return s;
}

// The scores of one job file: its reports' jobs matched with pcsim's by position.
void score_job_file(const fs::path& folder, const FioJobFileRuns& runs, std::vector<FioScore>& out) {
  const FioSimulation sim = simulate_fio(folder / runs.job_file, folder / "platform.toml", runs.memory_max);
  const std::vector<report::FioJobResult> simulated = report::fio_results(sim.scenario, sim.result);
  for (const FioRepetition& r : runs.repetitions) {
    if (r.jobs.size() != simulated.size()) {
      throw ConfigError(fmt::format("{}: fio reports {} job{}, pcsim reads {} from {} (group_reporting merges jobs: leave it out)",
                                    (folder / r.json_file).string(), r.jobs.size(), r.jobs.size() == 1 ? "" : "s", simulated.size(), runs.job_file));
    }
  }
  for (std::size_t j = 0; j < simulated.size(); ++j) {
    for (const bool read : {true, false}) {
      std::vector<double> measured;
      bool any = false;
      for (const FioRepetition& r : runs.repetitions) {
        const FioMeasuredDirection& d = read ? r.jobs[j].read : r.jobs[j].write;
        measured.push_back(static_cast<double>(d.bw_bytes));
        any = any || d.io_bytes > 0;
      }
      const report::FioDirection& p = read ? simulated[j].read : simulated[j].write;
      if (!any && p.bytes == 0) continue;  // neither did I/O this way
      out.push_back(score(runs.job_file, runs.repetitions.front().jobs[j].name, read ? "read" : "write", std::move(measured), p.bytes_per_second()));
    }
  }
}

std::string number_json(double v) { return std::isfinite(v) ? fmt::format("{}", v) : "null"; }

}  // namespace

FioSimulation simulate_fio(const fs::path& job, const fs::path& platform, std::int64_t memory_max) {
  RunInputs inputs;
  inputs.workflow.platform = platform.string();
  if (memory_max > 0) inputs.overrides.emplace_back("fio.memory_max", std::to_string(memory_max));
  FioSimulation sim{load_run_scenario(job.string(), inputs), {}};
  RunOptions options;
  options.cache_contents = false;
  sim.result = run_scenario(sim.scenario, options);
  return sim;
}

std::vector<FioScore> score_fio(const fs::path& folder, const std::vector<FioJobFileRuns>& runs) {
  std::vector<FioScore> scores;
  for (const FioJobFileRuns& f : runs) score_job_file(folder, f, scores);
  return scores;
}

std::string fio_scores_table(const std::vector<FioScore>& scores) {
  std::string out = fmt::format("{:<24} {:<16} {:<5} {:>10} {:>8} {:>10} {:>8}  {}\n", "job file", "job", "dir", "fio MB/s", "spread%", "pcsim MB/s",
                                "error%", "verdict");
  int within = 0;
  for (const FioScore& s : scores) {
    within += s.within ? 1 : 0;
    out += fmt::format("{:<24} {:<16} {:<5} {:>10.1f} {:>8.1f} {:>10.1f} {:>8} {}\n", s.job_file, s.job, s.direction, s.median / 1e6, s.spread * 100.0,
                       s.pcsim / 1e6, std::isfinite(s.error) ? fmt::format("{:+.1f}", s.error * 100.0) : "n/a", s.within ? "within" : "off");
  }
  out += fmt::format("{} of {} within max(15 %, spread) (fio MB/s: the median of the repetitions' bw_bytes; spread: (max - min) / median; error: "
                     "pcsim / fio - 1)\n",
                     within, scores.size());
  return out;
}

std::string fio_scores_json(const std::vector<FioScore>& scores) {
  std::string out = fmt::format("{{\"tolerance\": {}, \"scores\": [", kTolerance);
  for (std::size_t i = 0; i < scores.size(); ++i) {
    const FioScore& s = scores[i];
    std::string measured;
    for (std::size_t r = 0; r < s.measured.size(); ++r) measured += (r == 0 ? "" : ", ") + number_json(s.measured[r]);
    out += fmt::format(
        "{}\n  {{\"job_file\": {}, \"job\": {}, \"direction\": \"{}\", \"measured_bytes_per_second\": [{}], \"median_bytes_per_second\": {}, "
        "\"spread\": {}, \"pcsim_bytes_per_second\": {}, \"error\": {}, \"verdict\": \"{}\"}}",
        i == 0 ? "" : ",", text::json_string(s.job_file), text::json_string(s.job), s.direction, measured, number_json(s.median),
        number_json(s.spread), number_json(s.pcsim), number_json(s.error), s.within ? "within" : "off");
  }
  return out + "\n]}\n";
}

}  // namespace pagecache::validate
