#pragma once
// The fio job file reader's contract, as fuzz/fio_fuzzer.cpp checks it on every input and
// tests/scenario/fio_examples_test.cpp on the seeds and fio's examples: any bytes either read
// as a job file or are refused with ConfigError; any other exception, a crash, a hang or
// unbounded memory is a bug. What reads keeps the reader's promises
// (src/formats/fio/job_file.hpp), checked here without the reader's code.

#include "formats/fio/job_file.hpp"

#include <pagecache/error.hpp>

#include <cstddef>
#include <cstdint>
#include <exception>
#include <optional>
#include <set>
#include <string>

namespace pagecache::fuzz {

/// The limits inputs are read with: smaller than pcsim's, so that one input reads in well under
/// a second under the sanitizers.
inline formats::fio::FioLimits fio_fuzz_limits() {
  formats::fio::FioLimits limits;
  limits.max_jobs = 10'000;
  limits.max_files = 100'000;
  limits.max_entries = 1'000'000;
  limits.max_includes = 50;
  return limits;
}

/// ${A} is 4k, ${D} /tmp, every other variable unset.
inline std::optional<std::string> fio_fuzz_env(const std::string& name) {
  if (name == "A") return "4k";
  if (name == "D") return "/tmp";
  return std::nullopt;
}

/// "" if job `i` of `f` keeps the reader's promises, else the first one broken.
inline std::string fio_job_problem(const formats::fio::FioJobFile& f, std::size_t i) {
  const formats::fio::FioJob& j = f.jobs[i];
  const std::string at = "job " + std::to_string(i) + ": ";
  if (j.section.empty() || j.name.empty()) return at + "an empty section or name";
  if (j.numjobs < 1 || j.jobnum < 0 || j.jobnum >= j.numjobs) return at + "jobnum out of [0, numjobs)";
  // Clones follow their job: jobnum 0, then numjobs-1 ... 1.
  if (j.jobnum != 0 && (i == 0 || f.jobs[i - 1].numjobs != j.numjobs || f.jobs[i - 1].section != j.section)) return at + "a clone apart from its job";
  if (j.jobnum != 0 && f.jobs[i - 1].jobnum != (j.jobnum + 1) % j.numjobs) return at + "clones out of fio's order";
  if (j.jobnum == 0 && i > 0 && f.jobs[i - 1].jobnum > 1) return at + "a job before its predecessor's clones are all made";
  if (j.files.empty()) return at + "no file";
  for (const std::string& file : j.files) {
    if (file.empty() || file.size() > 8191) return at + "a file name empty or too long";
  }
  if (j.bs_read < 1 || j.bs_write < 1 || j.bs_read > (std::int64_t{2} << 30) || j.bs_write > (std::int64_t{2} << 30)) return at + "block size out of range";
  std::size_t previous = 0;
  for (std::size_t k = 0; k < j.after.size(); ++k) {
    if (j.after[k] >= i) return at + "waits for itself or a later job";
    if (k > 0 && j.after[k] <= previous) return at + "after not ascending";
    previous = j.after[k];
  }
  if (i > 0 && j.group < f.jobs[i - 1].group) return at + "groups not in order";
  if (j.rwmixread < 0 || j.rwmixread > 100) return at + "rwmixread out of range";
  for (int percent : {j.size_percent, j.offset_percent, j.offset_increment_percent, j.io_size_percent}) {
    if (percent < 0 || percent > 100) return at + "a percentage out of range";
  }
  if (j.size < 0 || j.filesize < 0 || j.offset < 0 || j.offset_increment < 0 || j.io_size < 0 || j.number_ios < 0) return at + "a negative size";
  const bool random = j.rw == formats::fio::FioRw::RandRead || j.rw == formats::fio::FioRw::RandWrite || j.rw == formats::fio::FioRw::RandReadWrite;
  if (random && j.rw_step < 1) return at + "a random mode's :N below 1";
  if (j.loops < 1 || j.iodepth < 1 || j.thinktime_blocks < 1 || j.file_service_step < 1) return at + "a count below 1";
  if (j.fsync < 0 || j.fdatasync < 0) return at + "a negative sync count";
  if (!(j.runtime >= 0 && j.ramp_time >= 0 && j.startdelay >= 0 && j.thinktime >= 0)) return at + "a negative time";
  if (j.time_based && !(j.runtime > 0)) return at + "time_based without runtime";
  const std::set<std::string> engines{"sync", "psync", "vsync", "pvsync", "pvsync2"};
  if (engines.count(j.ioengine) == 0) return at + "an engine pcsim does not model";
  return {};
}

/// "" if `f` keeps the reader's promises, else the first one broken.
inline std::string fio_file_problem(const formats::fio::FioJobFile& f, const formats::fio::FioLimits& limits) {
  if (f.jobs.empty()) return "no jobs";
  if (static_cast<std::int64_t>(f.jobs.size()) > limits.max_jobs) return "more jobs than the limit";
  for (std::size_t i = 0; i < f.jobs.size(); ++i) {
    std::string problem = fio_job_problem(f, i);
    if (!problem.empty()) return problem;
  }
  if (f.jobs.back().jobnum > 1) return "the last job's clones are not all made";
  return {};
}

/// "" if `text` read as the job file `path` either reads and keeps its promises or is refused
/// with a ConfigError that has a message; else what broke.
inline std::string check_fio_text(const std::string& text, const std::string& path) {
  const formats::fio::FioLimits limits = fio_fuzz_limits();
  try {
    return fio_file_problem(formats::fio::read_fio_job_file(text, path, fio_fuzz_env, limits), limits);
  } catch (const ConfigError& error) {
    return std::string(error.what()).empty() ? "a ConfigError without a message" : "";
  } catch (const std::exception& error) {
    return std::string("an exception other than ConfigError: ") + error.what();
  }
}

}  // namespace pagecache::fuzz
