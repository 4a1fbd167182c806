#pragma once
// The validation data readers' contract, as fuzz/validation_fuzzer.cpp checks it on every input
// and tests/validate/validation_data_test.cpp replays it on the seeds (fuzz/seeds/validation-*):
// any bytes, read as each file of validation/paper/ (src/validate/paper_data.hpp) and as each
// file `validate --here` keeps (src/validate/here_data.hpp), either read or are refused with a
// ConfigError whose message starts with "FILE:LINE:"; any other exception, a crash, a hang,
// unbounded memory or a sanitizer report is a bug. What reads holds finite numbers only, in
// the ranges the readers promise. Bytes with two form feeds are also read as a kept folder:
// runs.csv, phases.csv and memory.csv between them, checked against each other.

#include <pagecache/error.hpp>
#include <pagecache/units.hpp>

#include "validate/here_data.hpp"
#include "validate/paper_data.hpp"

#include <cctype>
#include <cmath>
#include <functional>
#include <set>
#include <string>
#include <tuple>
#include <vector>

namespace pagecache::fuzz {

/// "" if `message` starts with "<file>:<line>:", else what is wrong with it.
inline std::string unlocated(const std::string& message, const std::string& file) {
  std::size_t i = file.size() + 1;
  const bool named = message.compare(0, i, file + ":") == 0 && i < message.size() && std::isdigit(static_cast<unsigned char>(message[i]));
  while (i < message.size() && std::isdigit(static_cast<unsigned char>(message[i]))) ++i;
  if (!named || i >= message.size() || message[i] != ':') return "a ConfigError without " + file + ":LINE: " + message;
  return {};
}

/// "" if `read` returns or throws a ConfigError naming `file` and a line; what it returned is
/// checked by `check` ("" if it keeps the promises). Other exceptions are not caught: in the
/// fuzzer they end the process where they were thrown, in a test Catch2 reports them.
template <class T>
std::string check_reader(const std::string& file, const std::function<T()>& read, const std::function<std::string(const T&)>& check) {
  T value;
  try {
    value = read();
  } catch (const ConfigError& e) {
    return unlocated(e.what(), file);
  }
  const std::string broken = check(value);
  return broken.empty() ? broken : file + ": " + broken;
}

inline bool within(double v, double lo, double hi) { return std::isfinite(v) && v >= lo && v <= hi; }
inline bool phase_name(const std::string& p) { return p == "read" || p == "compute" || p == "write"; }
// A duration the readers keep: finite, up to 10^9 s; a real read's or write's above 0.
inline bool duration_ok(double d, bool real, const std::string& phase) {
  return within(d, 0.0, units::kMaxSeconds) && (!real || phase == "compute" || d > 0.0);
}

inline std::string check_phase_times(const validate::DataFile<validate::PhaseTime>& f, bool real) {
  std::set<std::tuple<int, int, std::string>> seen;
  for (const validate::PhaseTime& p : f.rows) {
    if (p.line < 2 || p.size_gb < 1 || p.task < 1 || !phase_name(p.phase)) return "a row with a bad line, size, task or phase";
    if (!within(p.end_s, 0.0, units::kMaxSeconds) || !duration_ok(p.duration_s, real, p.phase)) return "a bad end or duration";
    if (!seen.insert({p.size_gb, p.task, p.phase}).second) return "a phase twice";
  }
  return {};
}

inline std::string check_memory_profile(const validate::DataFile<validate::MemoryProfileRow>& f) {
  const double max_mb = static_cast<double>(units::kMaxBytes) / 1e6;
  for (const validate::MemoryProfileRow& m : f.rows) {
    if (m.line < 2 || m.size_gb < 1 || !within(m.time_s, -units::kMaxSeconds, units::kMaxSeconds)) return "a row with a bad line, size or time";
    for (const double mb : {m.cached_mb, m.dirty_mb, m.shmem_mb}) {
      if (!within(mb, 0.0, max_mb)) return "an amount of memory that is not finite, negative or beyond 1 EiB";
    }
  }
  return {};
}

inline std::string check_cache_contents(const validate::DataFile<validate::CachedFileRow>& f) {
  for (const validate::CachedFileRow& c : f.rows) {
    if (c.line < 2 || c.size_gb < 1 || c.after_task.empty() || c.file.empty() || !phase_name(c.after_phase)) return "a row with a bad key";
    for (const char d : c.after_task) {
      if (!std::isdigit(static_cast<unsigned char>(d))) return "a task that is not a number";
    }
    if (!within(c.cached_gb, 0.0, static_cast<double>(units::kMaxBytes) / 1e9)) return "a cached amount that is not finite or negative";
  }
  return {};
}

inline std::string check_concurrent(const validate::DataFile<validate::ConcurrentPhase>& f, bool real) {
  for (const validate::ConcurrentPhase& p : f.rows) {
    if (p.line < 2 || p.n < 1 || (real ? p.repetition < 1 : p.repetition != 0) || !phase_name(p.phase)) return "a row with a bad key";
    if (!duration_ok(p.duration_s, real, p.phase)) return "a bad duration";
  }
  return {};
}

inline std::string check_kept_run(const calibrate::RealRun& r) {
  const auto& c = r.spec;
  if (c.name.empty() || c.pipelines < 1 || c.tasks < 1 || c.file_size < 1 || c.chunk < 1 || !within(c.compute, 0.0, units::kMaxSeconds))
    return "a case with a bad name, count, size or compute time";
  if (r.repetition < 1 || !(r.makespan > 0.0 && within(r.makespan, 0.0, units::kMaxSeconds)) || r.memory_total < 1 || r.in_use_at_start < 0 || r.free_at_start < 0)
    return "a run with a bad repetition, makespan or memory";
  if (!(r.others_busy_cores == -1.0 || within(r.others_busy_cores, 0.0, 1e6)) || !(r.steal_pct == -1.0 || within(r.steal_pct, 0.0, 100.0)) ||
      r.reported < -1)
    return "a run with a bad activity figure";
  return {};
}

inline std::string check_kept_phase(const calibrate::RealPhase& p) {
  if (p.pipeline < 1 || p.task < 1 || !phase_name(p.phase)) return "a phase with a bad pipeline, task or name";
  if (!within(p.start, 0.0, units::kMaxSeconds) || !within(p.end, p.start, units::kMaxSeconds)) return "a phase with a bad start or end";
  if (p.phase != "compute" && !(p.end > p.start)) return "a read or write of no time";
  return {};
}

inline std::string check_kept_sample(const calibrate::MemorySample& s) {
  if (!within(s.time, 0.0, units::kMaxSeconds) || s.free < 0 || s.cached < 0 || s.dirty < 0 || s.writeback < 0) return "a bad memory sample";
  return {};
}

/// "" if `check` holds for every row's `value` (or the row itself), else the first break.
template <class Rows, class Check>
std::string every_row(const Rows& rows, const Check& check) {
  for (const auto& r : rows) {
    if (std::string b = check(r); !b.empty()) return b;
  }
  return {};
}

/// "" if the three texts read as a kept folder keep the contract, else what broke: a fault named
/// by one of the files and a line; what reads has every run's phases and a memory sample.
inline std::string check_kept_folder(const std::string& runs, const std::string& phases, const std::string& memory) {
  validate::KeptTexts t;
  t.runs = runs;
  t.phases = phases;
  t.memory = memory;
  validate::HereMeasurements m;
  try {
    m = validate::parse_here(t);
  } catch (const ConfigError& e) {
    const std::string message = e.what();
    for (const char* file : {"runs.csv", "phases.csv", "memory.csv"}) {
      if (unlocated(message, file).empty()) return {};
    }
    return "a kept folder refused without FILE:LINE: " + message;
  }
  if (m.runs.empty()) return "a kept folder without runs";
  for (const calibrate::RealRun& r : m.runs) {
    if (std::string b = check_kept_run(r); !b.empty()) return "kept folder: " + b;
    const auto phases_expected = static_cast<std::size_t>(r.spec.pipelines) * static_cast<std::size_t>(r.spec.tasks) * 3;
    if (r.phases.size() != phases_expected) return "kept folder: a run without all its phases";
    if (std::string b = every_row(r.phases, check_kept_phase); !b.empty()) return "kept folder: " + b;
    if (r.memory.empty()) return "kept folder: a run without a memory sample";
    if (std::string b = every_row(r.memory, check_kept_sample); !b.empty()) return "kept folder: " + b;
    for (std::size_t i = 1; i < r.memory.size(); ++i) {
      if (r.memory[i].time < r.memory[i - 1].time) return "kept folder: memory samples out of time order";
    }
  }
  return {};
}

/// "" if `text` keeps the contract as every file, else what broke.
inline std::string check_validation_text(const std::string& text) {
  using namespace validate;
  std::string broken;
  const auto add = [&](const std::string& b) {
    if (broken.empty()) broken = b;
  };
  for (const bool real : {true, false}) {
    add(check_reader<DataFile<PhaseTime>>(
        "exp1_phase_times.csv", [&] { return read_exp1_phase_times(text, "exp1_phase_times.csv", real); },
        [&](const DataFile<PhaseTime>& f) { return check_phase_times(f, real); }));
    add(check_reader<DataFile<ConcurrentPhase>>(
        "concurrent_phase_times.csv", [&] { return read_concurrent_phase_times(text, "concurrent_phase_times.csv", real); },
        [&](const DataFile<ConcurrentPhase>& f) { return check_concurrent(f, real); }));
  }
  add(check_reader<DataFile<MemoryProfileRow>>(
      "exp1_real_memory_profile.csv", [&] { return read_exp1_memory_profile(text, "exp1_real_memory_profile.csv"); }, check_memory_profile));
  add(check_reader<DataFile<CachedFileRow>>(
      "exp1_real_cache_contents.csv", [&] { return read_exp1_cache_contents(text, "exp1_real_cache_contents.csv"); }, check_cache_contents));
  add(check_reader<std::vector<KeptRun>>("runs.csv", [&] { return read_kept_runs(text, "runs.csv"); },
                                         [](const std::vector<KeptRun>& rows) { return every_row(rows, [](const KeptRun& k) { return check_kept_run(k.run); }); }));
  using Phases = std::vector<KeptRow<calibrate::RealPhase>>;
  add(check_reader<Phases>("phases.csv", [&] { return read_kept_phases(text, "phases.csv"); }, [](const Phases& rows) {
    return every_row(rows, [](const KeptRow<calibrate::RealPhase>& r) { return check_kept_phase(r.value); });
  }));
  using Samples = std::vector<KeptRow<calibrate::MemorySample>>;
  add(check_reader<Samples>("memory.csv", [&] { return read_kept_memory(text, "memory.csv"); }, [](const Samples& rows) {
    return every_row(rows, [](const KeptRow<calibrate::MemorySample>& r) { return check_kept_sample(r.value); });
  }));
  // runs.csv, phases.csv and memory.csv of one folder, between form feeds.
  const std::size_t first = text.find('\f');
  const std::size_t second = first == std::string::npos ? first : text.find('\f', first + 1);
  if (second != std::string::npos && text.find('\f', second + 1) == std::string::npos) {
    add(check_kept_folder(text.substr(0, first), text.substr(first + 1, second - first - 1), text.substr(second + 1)));
  }
  return broken;
}

}  // namespace pagecache::fuzz
