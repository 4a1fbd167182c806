#include "sweep/executor.hpp"

#include "report/outputs.hpp"
#include "report/output_file.hpp"
#include "formats/common/text_file.hpp"
#include "sweep/result_line.hpp"
#include "sweep/results_file.hpp"
#include "sweep/results_folder.hpp"

#include <pagecache/error.hpp>
#include <pagecache/run.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <mutex>
#include <new>
#include <thread>
#include <unordered_set>
#include <vector>

#include <sys/stat.h>

namespace pagecache::sweep {

namespace {

namespace fs = std::filesystem;

std::optional<std::size_t> whole_number(const std::string& text) {
  if (text.empty() || text.size() > 12 || text.find_first_not_of("0123456789") != std::string::npos) return std::nullopt;
  return static_cast<std::size_t>(std::stoull(text));
}

}  // namespace

// One run, start to end; any failure is its result, with pcsim run's exit code for it.
RunRecord execute_run(const Sweep& plan, const Run& run, RunOptions run_options, const std::string& outputs_dir) {
  const auto start = std::chrono::steady_clock::now();
  const auto wall = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  int code = 1;
  std::string error;
  try {
    const Scenario scenario = plan.scenario(run);
    run_options.cache_contents = !outputs_dir.empty();
    const RunResult result = run_scenario(scenario, run_options);
    if (!outputs_dir.empty()) report::write_outputs(outputs_dir, scenario, result, {.report = false, .activity = nullptr, .more = {}});
    return {result_line(plan.fingerprint(), run, &result, 0, {}, wall()), false};
  } catch (const ConfigError& e) {
    code = 2;
    error = e.what();
  } catch (const SimulationError& e) {
    error = std::string("simulation failed: ") + e.what();
  } catch (const InvariantError& e) {
    code = 3;
    error = std::string("internal error: ") + e.what();
  } catch (const std::bad_alloc&) {
    code = 3;
    error = "out of memory";
  } catch (const std::exception& e) {
    error = e.what();
  }
  return {result_line(plan.fingerprint(), run, nullptr, code, error, wall()), true};
}

// out_dir/sweep-plan.json: written by the first shard, the same for every other. Everything
// in the folder is read and checked before the plan is written.
std::unordered_set<std::string> prepare_out_dir(const Sweep& plan, const std::string& out_dir) {
  std::error_code ec;
  if (fs::exists(out_dir, ec) && !fs::is_directory(out_dir, ec)) throw ConfigError(fmt::format("--out {}: is not a folder", out_dir));
  fs::create_directories(out_dir);
  const fs::path path = fs::path(out_dir) / "sweep-plan.json";
  const std::string text = plan.json();
  std::optional<std::string> there;
  if (struct stat st {}; ::lstat(path.c_str(), &st) == 0) {
    if (!S_ISREG(st.st_mode)) {
      throw ConfigError(fmt::format("--out {}: its sweep-plan.json {}, not the plan pcsim wrote: left as it is; give another --out", out_dir,
                                    S_ISLNK(st.st_mode) ? "is a symbolic link" : S_ISDIR(st.st_mode) ? "is a folder" : "is not a regular file"));
    }
    there = formats::read_text_file(path.string(), "sweep plan");
  }
  if (there && *there != text) {
    const Sweep before = Sweep::from_json(*there, path.string());
    // The runs there are this sweep's only if they ran on the same base: a scenario edited
    // since, or another one, would mix two bases in one results.csv.
    if (const std::string changes = base_changes(before.base(), plan.base()); !changes.empty()) {
      throw ConfigError(fmt::format("--out {}: holds the results of a sweep of another base scenario ({}): {}; give another --out", out_dir,
                                    path.string(), changes));
    }
    // A sweep grown by new axis values (its runs keep their ids) goes on in the same folder;
    // one that drops a run of the folder's sweep would leave results merge cannot place.
    std::unordered_set<std::string> now;
    for (std::size_t i = 0; i < plan.size(); ++i) now.insert(plan.run(i).id);
    for (std::size_t i = 0; i < before.size(); ++i) {
      const Run run = before.run(i);
      if (now.count(run.id) == 0) {
        throw ConfigError(fmt::format("--out {}: holds the results of another sweep, with runs this one lacks (run {}, of {}): give another --out",
                                      out_dir, run.id, path.string()));
      }
    }
  }
  // Every shard's results, of any split: a run there is done, whichever split runs next.
  std::unordered_set<std::string> done;
  for_each_result(out_dir, plan.fingerprint(), [&](const std::string& id, std::string_view, const std::string&, std::size_t) { done.insert(id); });
  // Written whole, then renamed: concurrent shards write the same bytes.
  if (!there || *there != text) report::write_output_file(path.string(), text, "--out");
  return done;
}

Shard parse_shard(const std::string& text) {
  const auto slash = text.find('/');
  const auto index = slash == std::string::npos ? std::nullopt : whole_number(text.substr(0, slash));
  const auto count = slash == std::string::npos ? std::nullopt : whole_number(text.substr(slash + 1));
  if (!index || !count || *count == 0 || *index >= *count) {
    throw ConfigError(fmt::format("--shard '{}': expected I/N with 0 <= I < N, e.g. 0/4", text));
  }
  return {*index, *count};
}

std::optional<Shard> shard_from_slurm() {
  const char* id = std::getenv("SLURM_ARRAY_TASK_ID");
  const char* count = std::getenv("SLURM_ARRAY_TASK_COUNT");
  const char* min = std::getenv("SLURM_ARRAY_TASK_MIN");
  if (id == nullptr || count == nullptr) return std::nullopt;
  const auto i = whole_number(id), n = whole_number(count), m = whole_number(min != nullptr ? min : "0");
  if (!i || !n || !m || *i < *m || *i - *m >= *n) {
    throw ConfigError(fmt::format("the Slurm array task {} of {} (from {}) is not a shard: give --shard I/N", id, count, min != nullptr ? min : "0"));
  }
  return Shard{*i - *m, *n};
}

std::string results_path(const std::string& out_dir, const Shard& shard) {
  return (fs::path(out_dir) / fmt::format("results-{}-of-{}.jsonl", shard.index, shard.count)).string();
}

SweepOutcome run_sweep(const Sweep& plan, const SweepOptions& options) {
  if (options.out_dir.empty()) throw ConfigError("sweep run: --out DIR is needed");
  const std::unordered_set<std::string> done = prepare_out_dir(plan, options.out_dir);
  SweepOutcome outcome;
  outcome.results = results_path(options.out_dir, options.shard);
  ResultsFile results(outcome.results, plan.fingerprint());
  // The shard's runs are made as workers take them, not held (a shard of a plan of 10^9 runs
  // would not fit in memory); a first walk counts those still to do, for progress.
  const std::size_t shard_runs = plan.size() > options.shard.index ? (plan.size() - options.shard.index - 1) / options.shard.count + 1 : 0;
  const auto run_at = [&](std::size_t k) { return plan.run(options.shard.index + k * options.shard.count); };
  const auto is_done = [&](const Run& run) { return done.count(run.id) != 0 || results.done().count(run.id) != 0; };
  std::size_t to_do = 0;
  for (std::size_t k = 0; k < shard_runs; ++k) to_do += is_done(run_at(k)) ? 0 : 1;
  outcome.skipped = shard_runs - to_do;
  std::atomic<std::size_t> next{0};
  std::mutex lock;  // the results file, the outcome, progress
  std::exception_ptr broken;
  const auto worker = [&] {
    for (std::size_t k = next++; k < shard_runs; k = next++) {
      const Run run = run_at(k);
      {
        const std::lock_guard guard(lock);  // results.done() grows as runs end
        if (is_done(run)) continue;
      }
      const RunRecord finished =
          execute_run(plan, run, {}, options.keep_outputs ? (fs::path(options.out_dir) / "runs" / run.id).string() : std::string());
      const std::lock_guard guard(lock);
      if (broken) return;
      try {
        results.append(finished.line);
      } catch (...) {
        broken = std::current_exception();
        next = shard_runs;
        return;
      }
      ++outcome.ran;
      if (finished.failed) ++outcome.failed;
      if (options.progress) options.progress(outcome.ran, to_do);
    }
  };
  const unsigned jobs = std::max(1u, std::min<unsigned>(options.jobs, static_cast<unsigned>(std::clamp<std::size_t>(to_do, 1, 1024))));
  std::vector<std::thread> threads;
  for (unsigned j = 1; j < jobs; ++j) threads.emplace_back(worker);
  worker();
  for (std::thread& t : threads) t.join();
  if (broken) std::rethrow_exception(broken);
  return outcome;
}

}  // namespace pagecache::sweep
