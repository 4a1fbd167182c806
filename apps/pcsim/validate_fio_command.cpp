#include "validate_fio_command.hpp"

#include "calibrate/measure.hpp"
#include "calibrate/memory_cgroup.hpp"
#include "calibrate/real_fio.hpp"
#include "calibrate/scratch.hpp"
#include "formats/fio/job_file.hpp"
#include "formats/common/text_file.hpp"
#include "status_line.hpp"
#include "validate/fio_kept.hpp"
#include "validate/fio_score.hpp"

#include <pagecache/error.hpp>
#include <pagecache/scenario_file.hpp>
#include <pagecache/units.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <optional>
#include <set>
#include <sstream>

namespace pcsim {

namespace {

namespace fs = std::filesystem;
namespace val = pagecache::validate;

void write_file(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out) throw pagecache::Error(fmt::format("cannot write {}", path.string()));
}

// A job file pcsim would not run, or one it estimates to run longer than fio may, is refused
// before anything runs.
void check_job(const fs::path& job, const fs::path& platform, int timeout, std::int64_t memory_max) {
  const val::FioSimulation sim = val::simulate_fio(job, platform, memory_max);
  if (sim.result.summary.makespan > timeout) {
    throw pagecache::ConfigError(fmt::format("{}: pcsim estimates {:.0f} s for one run, beyond --fio-timeout {} s: give a shorter job or a longer "
                                             "--fio-timeout",
                                             job.string(), sim.result.summary.makespan, timeout));
  }
}

// Before a calibration, the job files are loaded on a stand-in (pcsim refuses a job file for
// what it asks, not for the machine), so that a refused one stops everything before it runs.
constexpr const char* kStandInPlatform = R"([[hosts]]
name = "host"
memory = "8 GB"
memory_read_bw = "1 GB/s"
memory_write_bw = "1 GB/s"
[[hosts.disks]]
name = "disk"
read_bw = "100 MB/s"
write_bw = "100 MB/s"
capacity = "1 TB"
)";

void check_loads(const std::string& job, const fs::path& dir, std::int64_t memory_max) {
  const pagecache::calibrate::Scratch scratch(dir, "pcsim-fio-check");
  write_file(scratch.file("platform.toml"), kStandInPlatform);
  pagecache::RunInputs inputs;
  inputs.workflow.platform = scratch.file("platform.toml").string();
  if (memory_max > 0) inputs.overrides.emplace_back("fio.memory_max", std::to_string(memory_max));
  pagecache::load_run_scenario(job, inputs);
}

// --memory-max in bytes; 0 if not given.
std::int64_t memory_max_of(const ValidateHereOptions& o) {
  if (o.memory_max.empty()) return 0;
  std::int64_t bytes = 0;
  try {
    bytes = pagecache::units::parse_size(o.memory_max);
  } catch (const pagecache::ConfigError& e) {
    throw pagecache::ConfigError(fmt::format("--memory-max: {}", e.what()));
  }
  if (bytes < (std::int64_t{1} << 20)) throw pagecache::ConfigError(fmt::format("--memory-max {}: at least 1 MiB", o.memory_max));
  return bytes;
}

// fio runs in a folder pcsim makes and removes: a job file whose files lie outside it would
// leave them (or write over others) where pcsim cleans nothing, and one that includes others
// would not be whole in its copy kept beside the measurements.
void check_kept_inside(const std::string& job) {
  const pagecache::formats::fio::FioJobFile file = pagecache::formats::fio::read_fio_job_file(job);
  for (const pagecache::formats::fio::FioJob& j : file.jobs) {
    for (const std::string& name : j.files) {
      const fs::path path(name);
      if (path.is_absolute() || std::find(path.begin(), path.end(), "..") != path.end()) {
        throw pagecache::ConfigError(fmt::format("{}:{}: job '{}': its file '{}' is outside the folder fio runs in (made in --dir and removed "
                                                 "after): give filename= and directory= relative to it, without '..'",
                                                 job, j.line, j.name, name));
      }
    }
  }
  std::istringstream lines(pagecache::formats::read_text_file(job, "fio job file"));
  int number = 0;
  for (std::string line; std::getline(lines, line);) {
    ++number;
    const auto first = line.find_first_not_of(" \t");
    if (first != std::string::npos && line.compare(first, 8, "include ") == 0) {
      throw pagecache::ConfigError(fmt::format("{}:{}: include: the job file is kept whole beside its measurements: give it without includes", job, number));
    }
  }
}

// The job files as given: each one readable and of a name of its own (their copies share the
// folder), each loaded by pcsim: with --platform, on it and simulated (its estimated run
// within --fio-timeout), else on the stand-in (the estimate once calibrated); with
// --memory-max, in a memory group of it (one job only: pcsim refuses more).
void check_job_files(const ValidateHereOptions& o, std::int64_t memory_max) {
  std::set<std::string> names;
  for (const std::string& job : o.fio) {
    const std::string name = fs::path(job).filename().string();
    if (!names.insert(name).second) throw pagecache::ConfigError(fmt::format("--fio: two job files named {}: their measurements would share names", name));
    check_kept_inside(job);
    const std::size_t jobs = pagecache::formats::fio::read_fio_job_file(job).jobs.size();
    if (memory_max > 0 && jobs > 1) {
      throw pagecache::ConfigError(fmt::format("{}: --memory-max: {} jobs (numjobs clones count) in one memory cgroup are not modelled yet: give "
                                               "job files of one job each",
                                               job, jobs));
    }
    if (!o.platform.empty()) {
      check_job(job, o.platform, o.fio_timeout, memory_max);
    } else {
      check_loads(job, o.dir, memory_max);
    }
  }
}

std::string scored(const fs::path& folder) {
  const std::vector<val::FioScore> scores = val::score_fio(folder, val::load_fio_runs(folder));
  return val::fio_scores_table(scores);
}

}  // namespace

int run_validate_fio(const ValidateHereOptions& o) {
  check_here_folders(o);
  const std::int64_t memory_max = memory_max_of(o);
  check_job_files(o, memory_max);
  // One made and removed now: a user who may not make them learns it before anything runs.
  if (memory_max > 0) pagecache::calibrate::MemoryCgroup probe(memory_max);
  pagecache::calibrate::install_stop_handlers();
  StatusLine status(true);
  const std::string platform = here_platform_toml(o, status);
  const fs::path out = o.out;
  fs::create_directories(out);
  write_file(out / "platform.toml", platform);
  std::vector<val::FioJobFileRuns> runs;
  for (const std::string& job : o.fio) {
    const std::string name = fs::path(job).filename().string();
    fs::copy_file(job, out / name);
    if (o.platform.empty()) check_job(out / name, out / "platform.toml", o.fio_timeout, memory_max);
    runs.push_back({name, {}, memory_max});
  }
  const int repeat = o.repeat > 0 ? o.repeat : (o.quick ? 1 : 3);
  for (val::FioJobFileRuns& f : runs) {
    for (int rep = 1; rep <= repeat; ++rep) {
      if (status.due(true)) status.show(fmt::format("validate --here --fio: {} (repetition {} of {})", f.job_file, rep, repeat));
      std::optional<pagecache::calibrate::MemoryCgroup> cgroup;  // a fresh one per run: its peak is that run's
      if (memory_max > 0) cgroup.emplace(memory_max);
      const pagecache::calibrate::RealFio fio =
          pagecache::calibrate::run_real_fio(out / f.job_file, o.dir, o.fio_timeout, o.quick ? 6.0 : 40.0, "fio", cgroup ? &*cgroup : nullptr);
      if (fio.reporting_settled == 0) {
        status.clear();
        fmt::print(stderr, "pcsim: warning: {} repetition {}: free page reporting had not settled when fio started: part of its memory may have been warm\n",
                   f.job_file, rep);
      }
      const std::string json_file = fmt::format("fio-{}-{}.json", fs::path(f.job_file).stem().string(), rep);
      write_file(out / json_file, fio.json);
      f.repetitions.push_back({rep, json_file, val::parse_fio_report(fio.json, (out / json_file).string()), fio.peak_memory});
    }
  }
  status.clear();
  // Kept first, then scored from what was kept: `validate --from` gives the same table.
  write_file(out / val::kFioManifest, val::fio_manifest(runs));
  const std::vector<val::FioScore> scores = val::score_fio(out, val::load_fio_runs(out));
  const std::string table = val::fio_scores_table(scores);
  write_file(out / "fio-scores.json", val::fio_scores_json(scores));
  write_file(out / "report.txt", table);
  fmt::print("{}measurements and scores: {} (score them again: pcsim validate --from {})\n", table, o.out, o.out);
  return 0;
}

int score_validate_fio(const std::string& folder) {
  fmt::print("{}", scored(folder));
  return 0;
}

}  // namespace pcsim
