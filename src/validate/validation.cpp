#include "validate/validation.hpp"

#include "text/json_string.hpp"
#include "validate/paper_data.hpp"

#include <pagecache/cache_policies.hpp>
#include <pagecache/error.hpp>
#include <pagecache/run.hpp>
#include <pagecache/scenario.hpp>
#include <pagecache/scenario_file.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

namespace pagecache::validate {

namespace {

Scenario load(const Options& o, const std::string& file, const std::vector<std::pair<std::string, std::string>>& overrides) {
  Scenario s = load_scenario(file, overrides, o.profile);
  for (HostConfig& h : s.hosts) {
    for (const auto& [key, value] : o.switches) {
      if (find_host_model_switch(key) != nullptr) {
        h.cache.set(key, value);
        continue;
      }
      const PolicyDeclaration* owner = cache_policy_with(key);
      if (owner == nullptr) throw ConfigError(fmt::format("--switch: unknown page-cache switch '{}'", key));
      // A host whose policy (or preset) has no such switch takes the policy that has it.
      const PolicyDeclaration* own = find_cache_policy(h.cache.policy);
      if (own == nullptr || (own->parameter(key) == nullptr && own->preset_of != owner->name)) {
        h.cache.policy = std::string(owner->name);
        h.cache.parameters.clear();
      }
      h.cache.set(key, value);
    }
  }
  return s;
}
double pct(double sim, double real) { return 100.0 * std::abs(sim - real) / real; }

// The error of `value` against a real duration the data gives, which the readers keep above 0
// and finite; one so short that the error overflows is refused rather than written as inf.
double error_against(double value, double real, const std::string& where) {
  const double e = pct(value, real);
  if (!std::isfinite(e)) {
    throw ConfigError(fmt::format("{}: {} s is too short to compare with: the error relative to it is not a finite number", where, real));
  }
  return e;
}

using Overrides = std::vector<std::pair<std::string, std::string>>;

Overrides with(const Options& o, Overrides more) {
  Overrides all = o.overrides;
  all.insert(all.end(), more.begin(), more.end());
  return all;
}

// --- Exp 1 ----------------------------------------------------------------------------------

// The memory each real Exp 1 run began with outside the page cache (the dataset's first atop
// sample, exp1_single/scenario.json: used - (cached - shmem)): the 20, 50 and 75 GB runs had
// 5.1 GB of tmpfs, the 100 GB run 2.1 GB, beside the system's own 1.95 GB. The measured
// cluster starts from it; the paper profile models WRENCH-cache, which starts empty.
std::string exp1_memory_in_use(int size_gb) { return size_gb == 100 ? "\"4020 MB\"" : "\"7069 MB\""; }

// The rows of `data` for one file size; some are needed.
template <class R>
std::vector<const R*> rows_of_size(const DataFile<R>& data, int size_gb, const char* what) {
  std::vector<const R*> rows;
  for (const R& r : data.rows)
    if (r.size_gb == size_gb) rows.push_back(&r);
  if (rows.empty()) throw ConfigError(fmt::format("{}: no row with file_size_gb {}: the {} GB run's {} are needed", data.file, size_gb, size_gb, what));
  return rows;
}

using PhaseKey = std::pair<int, std::string>;  // task, phase

std::map<PhaseKey, const PhaseTime*> by_phase(const std::vector<const PhaseTime*>& rows) {
  std::map<PhaseKey, const PhaseTime*> out;
  for (const PhaseTime* r : rows) out[{r->task, r->phase}] = r;
  return out;
}

const PhaseTime& phase_row(const std::map<PhaseKey, const PhaseTime*>& rows, const PhaseKey& key, const std::string& file, int size_gb) {
  const auto it = rows.find(key);
  if (it == rows.end()) {
    throw ConfigError(fmt::format("{}: no row with file_size_gb {}, task {}, phase {}: the simulated run has that phase", file, size_gb,
                                  key.first, key.second));
  }
  return *it->second;
}

CaseResult exp1(const Options& o, const PaperData& data, int size_gb, double cpu_seconds) {
  CaseResult c;
  c.name = fmt::format("exp1_{}gb", size_gb);
  const auto real = by_phase(rows_of_size(data.exp1_real, size_gb, "phase times"));
  const auto wrench = by_phase(rows_of_size(data.exp1_wrench, size_gb, "phase times"));
  const std::vector<const MemoryProfileRow*> memory = rows_of_size(data.exp1_memory, size_gb, "memory samples");
  const std::vector<const CachedFileRow*> contents = rows_of_size(data.exp1_cache, size_gb, "cache contents");

  Overrides run_conditions = {{"pipelines.file_size", fmt::format("\"{} GB\"", size_gb)},
                              {"pipelines.cpu_time", fmt::format("\"{} s\"", cpu_seconds)}};
  if (o.profile == "linux") run_conditions.emplace_back("start.memory_in_use.node", exp1_memory_in_use(size_gb));
  const Scenario scenario = load(o, o.scenario_dir + "/exp1.toml", with(o, run_conditions));
  const RunResult run = run_scenario(scenario);

  // Real memory at an instant: the atop sample nearest in time. Page cache without tmpfs.
  auto real_memory_at = [&](double t) {
    const MemoryProfileRow* best = memory.front();
    for (const MemoryProfileRow* r : memory)
      if (std::abs(r->time_s - t) < std::abs(best->time_s - t)) best = r;
    return std::pair{(best->cached_mb - best->shmem_mb) * 1e6, best->dirty_mb * 1e6};
  };
  // Simulated memory at an instant: the compute node's at the sampling tick nearest in time,
  // which is its last row at or before that tick (a row is written only when it changed).
  const std::string& node = scenario.hosts.front().name;
  auto sim_memory_at = [&](double t) {
    const double interval = scenario.memory_sample_interval;
    const double tick = interval > 0.0 ? std::round(t / interval) * interval : t;
    const MemoryRow* best = nullptr;
    for (const MemoryRow& m : run.memory)
      if (run.host_name(m) == node && (best == nullptr || m.time <= tick)) best = &m;
    return std::pair{static_cast<double>(best->state.cached + best->state.reserved), static_cast<double>(best->state.dirty)};
  };
  const double total = static_cast<double>(scenario.hosts.front().memory);

  double sum = 0.0, wsum = 0.0, worst_dirty = 0.0, worst_cached = 0.0;
  int count = 0;
  c.table = fmt::format("  {:<6} {:<6} {:>9} {:>9} {:>8} {:>9} {:>8} | {:>9} {:>9} {:>9} {:>9}\n", "task", "phase", "real_s", "pcsim_s",
                        "err%", "wrench_s", "err%", "dirty_GB", "real", "cached_GB", "real");
  for (const PhaseRow& p : run.timeline) {
    if (p.phase == PhaseKind::Compute) continue;
    const std::string phase(to_string(p.phase));
    const std::string& task = run.task_name(p);
    const auto key = std::pair{std::stoi(task), phase};
    const PhaseTime& r = phase_row(real, key, data.exp1_real.file, size_gb);
    const PhaseTime& w = phase_row(wrench, key, data.exp1_wrench.file, size_gb);
    const std::string where = fmt::format("{}:{}: column 'duration_s'", data.exp1_real.file, r.line);
    const double sim = p.end - p.start;
    const double e = error_against(sim, r.duration_s, where);
    const double we = error_against(w.duration_s, r.duration_s, where);
    sum += e;
    wsum += we;
    ++count;
    const auto [sim_cached, sim_dirty] = sim_memory_at(p.end);
    const auto [real_cached, real_dirty] = real_memory_at(r.end_s);
    worst_dirty = std::max(worst_dirty, 100.0 * std::abs(sim_dirty - real_dirty) / total);
    worst_cached = std::max(worst_cached, 100.0 * std::abs(sim_cached - real_cached) / total);
    c.figures.push_back({fmt::format("task {} {}", task, phase), r.duration_s, sim, w.duration_s});
    c.table += fmt::format("  {:<6} {:<6} {:>9.2f} {:>9.2f} {:>8.1f} {:>9.2f} {:>8.1f} | {:>9.1f} {:>9.1f} {:>9.1f} {:>9.1f}\n", task,
                           phase, r.duration_s, sim, e, w.duration_s, we, sim_dirty / 1e9, real_dirty / 1e9, sim_cached / 1e9,
                           real_cached / 1e9);
  }
  if (count == 0) throw ConfigError(fmt::format("{}/exp1.toml: its run has no read or write to compare with the real ones", o.scenario_dir));
  c.mean_error_pct = sum / count;
  c.wrench_mean_error_pct = wsum / count;
  c.extra.emplace_back("max_dirty_diff_pct_of_memory", worst_dirty);
  c.extra.emplace_back("max_cached_diff_pct_of_memory", worst_cached);

  double worst_file = 0.0;
  std::map<std::tuple<std::string, std::string, std::string>, double> sim_cache;
  for (const CacheRow& r : run.cache) {
    const PhaseRow& p = run.timeline[r.phase];
    sim_cache[{run.task_name(p), std::string(to_string(p.phase)), run.files[r.file]}] = static_cast<double>(r.cached) / 1e9;
  }
  for (const CachedFileRow* r : contents) {
    const auto it = sim_cache.find({r->after_task, r->after_phase, r->file});
    if (it != sim_cache.end()) worst_file = std::max(worst_file, std::abs(it->second - r->cached_gb));
  }
  c.extra.emplace_back("max_file_cache_diff_gb", worst_file);
  return c;
}

// --- Exp 2 and 3: per n, mean per-pipeline total read and write time -----------------------

struct PerN {
  double read = 0.0;
  double write = 0.0;
};

std::map<int, PerN> real_per_n(const DataFile<ConcurrentPhase>& data) {
  // Sum over pipelines and tasks, divided by n, averaged over repetitions.
  std::map<std::pair<int, int>, PerN> per_rep;
  for (const ConcurrentPhase& r : data.rows) {
    if (r.phase == "compute") continue;
    PerN& p = per_rep[{r.n, r.repetition}];
    (r.phase == "read" ? p.read : p.write) += r.duration_s;
  }
  std::map<int, PerN> sums;
  std::map<int, int> reps;
  for (const auto& [key, p] : per_rep) {
    sums[key.first].read += p.read / key.first;
    sums[key.first].write += p.write / key.first;
    ++reps[key.first];
  }
  for (auto& [n, p] : sums) {
    p.read /= reps[n];
    p.write /= reps[n];
  }
  if (sums.empty()) throw ConfigError(fmt::format("{}: no read or write rows: the real runs' durations are needed", data.file));
  return sums;
}

std::map<int, PerN> simulated_per_n(const DataFile<ConcurrentPhase>& data) {
  std::map<int, PerN> out;
  for (const ConcurrentPhase& r : data.rows) {
    if (r.phase == "read") out[r.n].read += r.duration_s / r.n;
    if (r.phase == "write") out[r.n].write += r.duration_s / r.n;
  }
  return out;
}

CaseResult concurrent(const Options& o, const std::string& name, const std::string& scenario_file, const DataFile<ConcurrentPhase>& real_data,
                      const DataFile<ConcurrentPhase>& wrench_data) {
  CaseResult c;
  c.name = name;
  const auto real = real_per_n(real_data);
  const auto wrench = simulated_per_n(wrench_data);
  for (const auto& [n, truth] : real) {
    if (wrench.count(n) == 0) {
      throw ConfigError(fmt::format("{}: no row with n_pipelines {}: the real runs ({}) have that number of pipelines", wrench_data.file, n,
                                    real_data.file));
    }
  }
  double r_sum = 0, w_sum = 0, wr_sum = 0, ww_sum = 0;
  c.table = fmt::format("  {:>3} {:>9} {:>9} {:>7} {:>9} {:>7} | {:>9} {:>9} {:>7} {:>9} {:>7}\n", "n", "read_real", "pcsim", "err%",
                        "wrench", "err%", "write_real", "pcsim", "err%", "wrench", "err%");
  for (const auto& [n, truth] : real) {
    const Scenario scenario = load(o, o.scenario_dir + "/" + scenario_file, with(o, {{"pipelines.count", std::to_string(n)}}));
    RunOptions options;
    options.cache_contents = false;
    const RunResult run = run_scenario(scenario, options);
    PerN sim;
    for (const PhaseRow& p : run.timeline) {
      if (p.phase == PhaseKind::Read) sim.read += (p.end - p.start) / n;
      if (p.phase == PhaseKind::Write) sim.write += (p.end - p.start) / n;
    }
    const PerN w = wrench.at(n);
    const std::string reads = fmt::format("{}: n_pipelines {}: the mean read time per pipeline,", real_data.file, n);
    const std::string writes = fmt::format("{}: n_pipelines {}: the mean write time per pipeline,", real_data.file, n);
    const double er = error_against(sim.read, truth.read, reads), ew = error_against(sim.write, truth.write, writes);
    const double wer = error_against(w.read, truth.read, reads), wew = error_against(w.write, truth.write, writes);
    r_sum += er;
    w_sum += ew;
    wr_sum += wer;
    ww_sum += wew;
    c.figures.push_back({fmt::format("n={} read", n), truth.read, sim.read, w.read});
    c.figures.push_back({fmt::format("n={} write", n), truth.write, sim.write, w.write});
    c.table += fmt::format("  {:>3} {:>9.2f} {:>9.2f} {:>7.1f} {:>9.2f} {:>7.1f} | {:>9.2f} {:>9.2f} {:>7.1f} {:>9.2f} {:>7.1f}\n", n,
                           truth.read, sim.read, er, w.read, wer, truth.write, sim.write, ew, w.write, wew);
  }
  const double count = static_cast<double>(real.size());
  c.read_mean_error_pct = r_sum / count;
  c.write_mean_error_pct = w_sum / count;
  c.mean_error_pct = (r_sum + w_sum) / (2 * count);
  c.wrench_read_mean_error_pct = wr_sum / count;
  c.wrench_write_mean_error_pct = ww_sum / count;
  c.wrench_mean_error_pct = (wr_sum + ww_sum) / (2 * count);
  return c;
}

}  // namespace

Report run(const Options& o) {
  // Every file read and checked before anything is simulated.
  const PaperData data = read_paper_data(o.data_dir);
  Report report;
  report.profile = o.profile.empty() ? "(the scenarios' own)" : o.profile;
  report.cases.push_back(exp1(o, data, 20, 28.0));
  report.cases.push_back(exp1(o, data, 100, 155.0));
  report.cases.push_back(concurrent(o, "exp2_local", "exp2.toml", data.exp2_real, data.exp2_wrench));
  report.cases.push_back(concurrent(o, "exp3_nfs", "exp3.toml", data.exp3_real, data.exp3_wrench));
  check_finite(report);
  return report;
}

void check_finite(const Report& report) {
  for (const CaseResult& c : report.cases) {
    const auto check = [&](double v, const std::string& what) {
      if (!std::isfinite(v)) throw InvariantError(fmt::format("validate: case {}: {} is {}, which JSON and HTML cannot hold", c.name, what, v));
    };
    check(c.mean_error_pct, "mean_error_pct");
    check(c.read_mean_error_pct, "read_mean_error_pct");
    check(c.write_mean_error_pct, "write_mean_error_pct");
    check(c.wrench_mean_error_pct, "wrench_cache_mean_error_pct");
    check(c.wrench_read_mean_error_pct, "wrench_cache_read_mean_error_pct");
    check(c.wrench_write_mean_error_pct, "wrench_cache_write_mean_error_pct");
    for (const auto& [key, value] : c.extra) check(value, key);
    for (const Figure& f : c.figures) {
      check(f.real, f.label + " real");
      check(f.simulated, f.label + " pcsim");
      check(f.wrench, f.label + " WRENCH-cache");
      check(pct(f.simulated, f.real), f.label + " error");
      check(pct(f.wrench, f.real), f.label + " WRENCH-cache error");
    }
  }
}

std::string Report::text() const {
  std::string out = fmt::format("pcsim validate, profile {}: the paper's experiments against the real runs\n", profile);
  for (const CaseResult& c : cases) {
    out += fmt::format("\n{}: mean error {:.1f} % (WRENCH-cache {:.1f} %)", c.name, c.mean_error_pct, c.wrench_mean_error_pct);
    if (c.read_mean_error_pct >= 0) {
      out += fmt::format("; read {:.1f} % (WRENCH-cache {:.1f} %), write {:.1f} % (WRENCH-cache {:.1f} %)", c.read_mean_error_pct,
                         c.wrench_read_mean_error_pct, c.write_mean_error_pct, c.wrench_write_mean_error_pct);
    }
    out += "\n";
    for (const auto& [key, value] : c.extra) out += fmt::format("  {} = {:.2f}\n", key, value);
    out += c.table;
  }
  return out;
}

std::string Report::json() const {
  check_finite(*this);
  std::string out = "[\n";
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const CaseResult& c = cases[i];
    out += fmt::format("  {{\"case\": {}, \"profile\": {}, \"mean_error_pct\": {:.4f}, \"wrench_cache_mean_error_pct\": {:.4f}",
                       text::json_string(c.name), text::json_string(profile), c.mean_error_pct, c.wrench_mean_error_pct);
    if (c.read_mean_error_pct >= 0) {
      out += fmt::format(
          ", \"read_mean_error_pct\": {:.4f}, \"write_mean_error_pct\": {:.4f}, \"wrench_cache_read_mean_error_pct\": {:.4f}, "
          "\"wrench_cache_write_mean_error_pct\": {:.4f}",
          c.read_mean_error_pct, c.write_mean_error_pct, c.wrench_read_mean_error_pct, c.wrench_write_mean_error_pct);
    }
    for (const auto& [key, value] : c.extra) out += fmt::format(", {}: {:.4f}", text::json_string(key), value);
    out += i + 1 < cases.size() ? "},\n" : "}\n";
  }
  return out + "]\n";
}

}  // namespace pagecache::validate
