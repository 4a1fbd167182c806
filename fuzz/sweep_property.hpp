#pragma once
// The sweep readers' contracts, as fuzz/sweep_fuzzer.cpp checks them on every input and
// tests/sweep/sweep_identity_test.cpp on the seeds (fuzz/seeds/sweep-*):
//   - a sweep file: any text either reads as a plan or is refused with ConfigError; a plan
//     has at least one run and no more than the limits allow, holds no more values than its
//     runs need (each axis counted before it is made), and reads back from its json() (what
//     sweep-plan.json holds) as the same runs on the same base;
//   - a results file: any bytes are either accepted or refused with ConfigError; what is
//     accepted is whole lines, each a result of the sweep, then at most a last line cut short
//     that may be dropped; every beginning of an accepted line may be dropped as cut short;
//     an accepted line written again by result_line() is accepted as the same run.
// Any other exception, a crash, a hang, unbounded memory or a sanitizer report is a bug.

#include "sweep/hash.hpp"
#include "sweep/sweep.hpp"
#include "sweep/result_line.hpp"
#include "sweep/results_file.hpp"

#include <pagecache/error.hpp>
#include <pagecache/run.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstddef>
#include <string>
#include <string_view>

namespace pagecache::fuzz {

/// The base fingerprint results inputs are read against (the seeds' "base").
inline constexpr std::string_view kFuzzResultsBase = "0123456789abcdef";

/// The limits sweep files are read with: a grid's size is only computed, but every axis
/// value is made and up to 64 of each are tried on the base, so axes are kept short; the base
/// is read with the scenario fuzzer's limits.
inline sweep::SweepLimits sweep_fuzz_limits() {
  sweep::SweepLimits limits;
  limits.runs = 1e6;
  limits.axis_values = 1e4;
  limits.scenario.max_tasks = 10'000;
  limits.scenario.max_files = 20'000;
  return limits;
}

/// "" if the sweep file `text` (read as if it were `source_name`) keeps the contract, else
/// what broke.
inline std::string check_sweep_text(const std::string& text, const std::string& source_name) {
  const sweep::SweepLimits limits = sweep_fuzz_limits();
  sweep::Sweep plan;
  try {
    plan = sweep::Sweep::parse(text, source_name, false, limits);
  } catch (const ConfigError&) {
    return {};
  }
  if (plan.size() < 1) return "a plan of no run";
  if (static_cast<double>(plan.size()) > limits.runs) return "a plan of " + std::to_string(plan.size()) + " runs, beyond the limit";
  // A grid holds its axes' values (their product is the runs; an axis of one value multiplies
  // by 1), points a value per key each.
  const double keys = static_cast<double>(plan.keys().size());
  if (static_cast<double>(plan.values_held()) > limits.runs + keys && static_cast<double>(plan.values_held()) > static_cast<double>(plan.size()) * keys) {
    return "the plan holds " + std::to_string(plan.values_held()) + " values for " + std::to_string(plan.size()) + " runs";
  }
  if (!sweep::is_hex16(plan.fingerprint()) || plan.fingerprint() != plan.base().fingerprint()) return "a fingerprint that is not its base's";
  const sweep::Run first = plan.run(0), last = plan.run(plan.size() - 1);
  if (!sweep::is_hex16(first.id) || !sweep::is_hex16(last.id)) return "a run id that is not 16 hex digits";
  sweep::Sweep again;
  try {
    again = sweep::Sweep::from_json(plan.json(), "sweep-plan.json");
  } catch (const ConfigError& e) {
    return std::string("json() does not read back: ") + e.what();
  }
  if (again.size() != plan.size() || again.keys() != plan.keys() || again.fingerprint() != plan.fingerprint() || again.run(0).id != first.id ||
      again.run(again.size() - 1).id != last.id || again.json() != plan.json()) {
    return "json() reads back as another plan";
  }
  return {};
}

/// The line `line` (accepted) as pcsim would write it again: its run and figures through
/// result_line().
inline std::string written_again(std::string_view line) {
  const nlohmann::json doc = nlohmann::json::parse(line);
  sweep::Run run;
  run.id = doc.at("id").get<std::string>();
  run.index = doc.at("run").get<std::size_t>();
  for (const auto& [key, value] : doc.at("overrides").items()) run.overrides.push_back({key, value.get<std::string>(), {}});
  if (doc.at("status") != "ok") {
    return sweep::result_line(doc.at("base").get<std::string>(), run, nullptr, doc.at("exit_code").get<int>(), doc.at("error").get<std::string>(),
                              doc.at("wall_s").get<double>());
  }
  RunResult result;
  RunSummary& s = result.summary;
  s.makespan = doc.at("makespan_s").get<double>();
  s.end_time = doc.at("end_time_s").get<double>();
  s.read.seconds = doc.at("read_s").get<double>();
  s.compute.seconds = doc.at("compute_s").get<double>();
  s.write.seconds = doc.at("write_s").get<double>();
  s.disk_read_bytes = doc.at("disk_read_bytes").get<std::int64_t>();
  s.cache_read_bytes = doc.at("cache_read_bytes").get<std::int64_t>();
  s.forced_flush_bytes = doc.at("forced_flush_bytes").get<std::int64_t>();
  s.periodic_flush_bytes = doc.at("periodic_flush_bytes").get<std::int64_t>();
  s.evicted_bytes = doc.at("evicted_bytes").get<std::int64_t>();
  s.peak_dirty_bytes = doc.at("peak_dirty_bytes").get<std::int64_t>();
  s.events = doc.at("events").get<std::uint64_t>();
  s.wall_seconds = doc.at("sim_wall_s").get<double>();
  return sweep::result_line(doc.at("base").get<std::string>(), run, &result, 0, {}, doc.at("wall_s").get<double>());
}

/// "" if the results file `bytes` keeps the contract (read against kFuzzResultsBase), else
/// what broke.
inline std::string check_results_bytes(std::string_view bytes) {
  sweep::ResultsText results;
  try {
    results = sweep::read_results_text(bytes, kFuzzResultsBase, "fuzz.jsonl");
  } catch (const ConfigError&) {
    return {};
  }
  if (results.whole > bytes.size() || (results.whole > 0 && bytes[results.whole - 1] != '\n')) return "the whole lines end elsewhere than a newline";
  if (bytes.substr(results.whole).find('\n') != std::string_view::npos) return "a newline after the whole lines";
  if (results.lines.size() != static_cast<std::size_t>(std::count(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(results.whole), '\n'))) {
    return "a line left out";
  }
  for (const sweep::ResultsText::Line& line : results.lines) {
    const sweep::LineCheck again = sweep::check_result_line(written_again(line.text), kFuzzResultsBase);
    if (!again.problem.empty() || again.id != line.id) return "line " + std::to_string(line.number) + " written again is refused: " + again.problem;
  }
  if (!results.lines.empty()) {
    // Every beginning of the first line (every one of a short line, 64 of a long one), as a
    // shard killed while writing it would leave it.
    const std::string_view line = results.lines.front().text;
    const std::size_t step = std::max<std::size_t>(1, line.size() / 64);
    for (std::size_t n = 1; n <= line.size(); n += step) {
      const sweep::LineCheck cut = sweep::check_cut_result_line(line.substr(0, n), kFuzzResultsBase);
      if (!cut.problem.empty()) return "its first " + std::to_string(n) + " bytes may not be dropped as cut short: " + cut.problem;
    }
  }
  return {};
}

}  // namespace pagecache::fuzz
