#include "validate/here.hpp"

#include <pagecache/error.hpp>
#include <pagecache/run.hpp>
#include <pagecache/scenario_file.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <string>

namespace pagecache::validate {

namespace {

using calibrate::MemorySample;
using calibrate::RealCase;
using calibrate::RealPhase;
using calibrate::RealRun;

constexpr std::int64_t MiB = 1 << 20;
constexpr double GB = 1e9;

std::int64_t whole_chunks(double bytes, std::int64_t chunk) {
  return std::max<std::int64_t>(chunk, static_cast<std::int64_t>(bytes / static_cast<double>(chunk)) * chunk);
}

std::string size_text(std::int64_t bytes) {
  if (bytes >= 1'000'000'000) return fmt::format("{:.2f} GB", static_cast<double>(bytes) / GB);
  return fmt::format("{:.0f} MB", static_cast<double>(bytes) / 1e6);
}

double mean(const std::vector<double>& v) {
  double sum = 0.0;
  for (double x : v) sum += x;
  return v.empty() ? 0.0 : sum / static_cast<double>(v.size());
}

// (max - min) / mean, in %: how far the repetitions are apart.
double spread_pct(const std::vector<double>& v) {
  if (v.size() < 2) return 0.0;
  const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
  const double m = mean(v);
  return m > 0.0 ? (*hi - *lo) / m * 100.0 : 0.0;
}

double error_pct(double simulated, double real) { return real > 0.0 ? std::abs(simulated - real) / real * 100.0 : 0.0; }

// The error against a real figure the files give (above 0: here_data.cpp), refused rather than
// printed as inf when the figure is so short that it overflows.
double finite_error(double simulated, double real, const std::string& what) {
  const double e = error_pct(simulated, real);
  if (!std::isfinite(e)) throw ConfigError(fmt::format("{}, {} s, is too short to compare with: the error relative to it is not a finite number", what, real));
  return e;
}

// --- Simulating a case -------------------------------------------------------------------------

struct Simulated {
  RunResult result;
  std::string host;
};

Simulated simulate(const std::string& platform, const RealCase& spec, std::int64_t in_use, std::int64_t warm) {
  const std::string text = fmt::format(
      "profile = \"linux\"\nmemory_sample_interval = \"0 s\"\n{}\n[pipelines]\ncount = {}\nfile_size = \"{} B\"\ntasks = {}\ncpu_time = \"{} s\"\n"
      "chunk_size = \"{} B\"\n",
      platform, spec.pipelines, spec.file_size, spec.tasks, spec.compute, spec.chunk);
  Scenario s = parse_scenario(text, "platform.toml + " + spec.name);
  if (s.hosts.empty()) throw ConfigError("platform.toml: no host");
  s.hosts[0].memory_in_use = std::clamp<std::int64_t>(in_use, 0, s.hosts[0].memory - 1);
  s.hosts[0].memory_freed_at_start = warm;
  RunOptions options;
  options.cache_contents = false;
  return Simulated{run_scenario(s, options), s.hosts[0].name};
}

// The host's memory in the simulation at `time` (the last row at or before it).
MemoryState simulated_memory(const RunResult& r, double time) {
  MemoryState state;
  for (const MemoryRow& row : r.memory) {
    if (row.time > time + 1e-9) break;
    state = row.state;
  }
  return state;
}

// The real memory at `time` (the first sample at or after it, else the last).
MemorySample real_memory(const RealRun& run, double time) {
  for (const MemorySample& s : run.memory) {
    if (s.time >= time) return s;
  }
  return run.memory.empty() ? MemorySample{} : run.memory.back();
}

// What else the machine did during the runs, and what its calibration noted about it.
std::string activity_notes(const HereMeasurements& m) {
  std::string out;
  double busiest = -1.0, steal = -1.0;
  double reported = -1.0;  // bytes; a sum of many runs' could overflow an integer
  const RealRun* busiest_run = nullptr;
  for (const RealRun& r : m.runs) {
    if (r.others_busy_cores > busiest) {
      busiest = r.others_busy_cores;
      busiest_run = &r;
    }
    steal = std::max(steal, r.steal_pct);
    if (r.reported >= 0) reported = std::max(reported, 0.0) + static_cast<double>(r.reported);
  }
  if (busiest > 0.2 && busiest_run != nullptr) {
    out += fmt::format("note: other work kept up to {:.2f} cores busy during a run ({} repetition {}): other load, or the kernel's own threads "
                       "(writeback, reclaim)\n",
                       busiest, busiest_run->spec.name, busiest_run->repetition);
  }
  if (steal > 2.0) out += fmt::format("note: the hypervisor took up to {:.1f} % of the CPUs' time during a run (steal)\n", steal);
  if (reported > 0) {
    // Set, not in a comment: a line whose first word is the key.
    bool modelled = false;
    std::istringstream lines(m.platform_toml);
    for (std::string line; std::getline(lines, line);) {
      const auto first = line.find_first_not_of(" \t");
      if (first != std::string::npos && line.compare(first, 20, "memory_cold_fault_bw") == 0) modelled = true;
    }
    out += fmt::format("note: {:.1f} GB of free memory went back to the virtual machine's host during the runs (free page reporting): a "
                       "later first touch of it waits for the host, {}\n",
                       reported / GB,
                       modelled ? "which pcsim models with the platform's memory_cold_fault_bw (docs/model.md §6.16)"
                                : "which pcsim does not model: the platform has no memory_cold_fault_bw");
  }
  // The calibration's notes, kept in the platform file.
  std::istringstream platform(m.platform_toml);
  for (std::string line; std::getline(platform, line);) {
    if (line.rfind("# Note: ", 0) == 0) out += "calibration note: " + line.substr(8) + "\n";
  }
  return out;
}

}  // namespace

std::vector<RealCase> here_cases(std::int64_t available, bool quick) {
  if (quick) {
    return {RealCase{"exp1-quick", 1, 3, 64 * MiB, 0.1, 16 * MiB}, RealCase{"exp2-quick-2", 2, 3, 32 * MiB, 0.1, 16 * MiB}};
  }
  const std::int64_t chunk = 100'000'000;  // the paper's
  std::vector<RealCase> cases;
  for (const double share : {0.08, 0.2, 0.4}) {
    const std::int64_t size = whole_chunks(static_cast<double>(available) * share, chunk);
    // The paper's tasks computed 4.4 s per 3 GB; here half that rate, so that a run stays short.
    cases.push_back(RealCase{fmt::format("exp1-{:.0f}pct", share * 100), 1, 3, size, 0.75 * static_cast<double>(size) / GB, chunk});
  }
  const std::int64_t small = whole_chunks(static_cast<double>(available) * 0.012, chunk);
  for (const int n : {4, 8}) cases.push_back(RealCase{fmt::format("exp2-{}", n), n, 3, small, 0.75 * static_cast<double>(small) / GB, chunk});
  return cases;
}

std::vector<std::pair<std::string, std::string>> here_files(const HereMeasurements& m) {
  std::string runs =
      "case,pipelines,tasks,file_size,compute_s,chunk,repetition,makespan_s,memory_total,in_use_at_start,free_at_start,dropped_all_caches,"
      "others_busy_cores,steal_pct,reported_bytes,warm_at_start\n";
  std::string phases = "case,repetition,pipeline,task,phase,start_s,end_s\n";
  std::string memory = "case,repetition,time_s,free,cached,dirty,writeback\n";
  for (const RealRun& r : m.runs) {
    const RealCase& c = r.spec;
    runs += fmt::format("{},{},{},{},{:.6f},{},{},{:.6f},{},{},{},{},{:.3f},{:.2f},{},{}\n", c.name, c.pipelines, c.tasks, c.file_size, c.compute,
                        c.chunk, r.repetition, r.makespan, r.memory_total, r.in_use_at_start, r.free_at_start, r.dropped_all_caches ? 1 : 0,
                        r.others_busy_cores, r.steal_pct, r.reported, r.warm_at_start);
    for (const RealPhase& p : r.phases) {
      phases += fmt::format("{},{},{},{},{},{:.6f},{:.6f}\n", c.name, r.repetition, p.pipeline, p.task, p.phase, p.start, p.end);
    }
    for (const MemorySample& s : r.memory) {
      memory += fmt::format("{},{},{:.3f},{},{},{},{}\n", c.name, r.repetition, s.time, s.free, s.cached, s.dirty, s.writeback);
    }
  }
  return {{"platform.toml", m.platform_toml}, {"runs.csv", runs}, {"phases.csv", phases}, {"memory.csv", memory}};
}

std::string score_here(const HereMeasurements& m) {
  std::vector<std::string> order;
  std::map<std::string, std::vector<const RealRun*>> by_case;
  for (const RealRun& r : m.runs) {
    if (by_case[r.spec.name].empty()) order.push_back(r.spec.name);
    by_case[r.spec.name].push_back(&r);
  }
  std::string out;
  std::vector<double> makespan_errors, phase_errors;
  bool noisy = false, not_dropped = false;
  for (const std::string& name : order) {
    const std::vector<const RealRun*>& runs = by_case[name];
    const RealCase& spec = runs.front()->spec;
    std::vector<double> in_use, warm;
    for (const RealRun* r : runs) {
      in_use.push_back(static_cast<double>(r->in_use_at_start));
      // Not known: its inputs, written and then dropped from the cache just before it started.
      warm.push_back(static_cast<double>(r->warm_at_start >= 0 ? r->warm_at_start : spec.file_size * spec.pipelines));
      not_dropped = not_dropped || !r->dropped_all_caches;
    }
    const Simulated sim = simulate(m.platform_toml, spec, static_cast<std::int64_t>(mean(in_use)), static_cast<std::int64_t>(mean(warm)));
    std::vector<double> makespans;
    for (const RealRun* r : runs) makespans.push_back(r->makespan);
    const double makespan_error = finite_error(sim.result.summary.makespan, mean(makespans), fmt::format("runs.csv: case {}: the real makespan", name));
    makespan_errors.push_back(makespan_error);
    noisy = noisy || spread_pct(makespans) > 10.0;
    std::string table = "  task  phase   real_s  spread%   pcsim_s    err% |  dirty_GB    real | cached_GB    real\n";
    std::vector<double> errors;
    for (int task = 1; task <= spec.tasks; ++task) {
      for (const char* phase : {"read", "write"}) {
        // Per repetition, the mean over the pipelines; the phase's end: its last.
        std::vector<double> per_run;
        double real_end = 0.0;
        for (const RealRun* r : runs) {
          std::vector<double> durations;
          for (const RealPhase& p : r->phases) {
            if (p.task != task || p.phase != phase) continue;
            durations.push_back(p.end - p.start);
            if (r == runs.front()) real_end = std::max(real_end, p.end);
          }
          if (!durations.empty()) per_run.push_back(mean(durations));
        }
        std::vector<double> simulated;
        double sim_end = 0.0;
        for (const PhaseRow& row : sim.result.timeline) {
          if (sim.result.task_name(row) != std::to_string(task) || to_string(row.phase) != phase) continue;
          simulated.push_back(row.end - row.start);
          sim_end = std::max(sim_end, row.end);
        }
        if (per_run.empty() || simulated.empty()) continue;
        const double real = mean(per_run);
        const double error = finite_error(mean(simulated), real, fmt::format("phases.csv: case {}: the real {} of task {}", name, phase, task));
        errors.push_back(error);
        const MemorySample rm = real_memory(*runs.front(), real_end);
        const double cached_at_start = runs.front()->memory.empty() ? 0.0 : static_cast<double>(runs.front()->memory.front().cached);
        const MemoryState sm = simulated_memory(sim.result, sim_end);
        table += fmt::format("  {:<5} {:<6} {:>7.2f} {:>8.1f} {:>9.2f} {:>7.1f} | {:>9.2f} {:>7.2f} | {:>9.2f} {:>7.2f}\n", task, phase, real,
                             spread_pct(per_run), mean(simulated), error, static_cast<double>(sm.dirty) / GB,
                             static_cast<double>(rm.dirty) / GB, static_cast<double>(sm.cached) / GB,
                             (static_cast<double>(rm.cached) - cached_at_start) / GB);
      }
    }
    phase_errors.insert(phase_errors.end(), errors.begin(), errors.end());
    out += fmt::format("{}: {} pipeline{} of {} tasks, files of {}, {} repetition{}: makespan error {:.1f} % (real {:.2f} s, spread {:.1f} %; pcsim "
                       "{:.2f} s); mean phase error {:.1f} %\n",
                       name, spec.pipelines, spec.pipelines == 1 ? "" : "s", spec.tasks, size_text(spec.file_size), runs.size(),
                       runs.size() == 1 ? "" : "s", makespan_error, mean(makespans), spread_pct(makespans), sim.result.summary.makespan, mean(errors));
    out += table + "\n";
  }
  out += fmt::format("over {} cases: mean makespan error {:.1f} %, mean phase error {:.1f} % (real: mean of the repetitions; spread: (max - "
                     "min) / mean of them; cached: real Cached less its value at the start)\n",
                     order.size(), mean(makespan_errors), mean(phase_errors));
  if (noisy) out += "note: a case's repetitions differ by over 10 %: the machine was noisy (other load, a virtual machine's host), the errors less than they seem\n";
  if (not_dropped) {
    out += "note: not root: only this run's own files were dropped from the cache; other files' cached data stayed, which the kernel could "
           "reclaim and pcsim counted as free\n";
  }
  out += activity_notes(m);
  return out;
}

}  // namespace pagecache::validate
