#include "validate/here_data.hpp"

#include "validate/csv.hpp"

#include <pagecache/error.hpp>
#include <pagecache/scenario_file.hpp>
#include <pagecache/units.hpp>

#include <fmt/format.h>

#include <climits>
#include <cmath>
#include <filesystem>
#include <map>
#include <tuple>

namespace pagecache::validate {

namespace {

using calibrate::MemorySample;
using calibrate::RealCase;
using calibrate::RealPhase;
using calibrate::RealRun;
using Row = CsvTable::Row;

double seconds(const Row& r, const char* column, Sign sign) {
  const double v = r.number(column, sign);
  if (v > units::kMaxSeconds) r.fail(column, fmt::format("{} s is beyond 10^9 s, the longest duration pcsim takes", v));
  return v;
}

std::int64_t bytes(const Row& r, const char* column, std::int64_t min = 0) { return r.whole(column, min, units::kMaxBytes); }

// A figure of the machine's activity: -1 (not measured) or from 0 to `max`.
double activity(const Row& r, const char* column, double max) {
  const double v = r.number(column);
  if (v != -1.0 && (v < 0.0 || v > max)) r.fail(column, fmt::format("{} is neither -1 (not measured) nor from 0 to {}", v, max));
  return v;
}

std::string name_of(const std::string& file) { return std::filesystem::path(file).filename().string(); }

}  // namespace

std::vector<KeptRun> read_kept_runs(std::string_view text, const std::string& file) {
  // The last four columns came later: an older folder lacks them.
  const CsvTable t(text, file,
                   {"case", "pipelines", "tasks", "file_size", "compute_s", "chunk", "repetition", "makespan_s", "memory_total", "in_use_at_start",
                    "free_at_start", "dropped_all_caches"},
                   {"others_busy_cores", "steal_pct", "reported_bytes", "warm_at_start"});
  const std::int64_t max_tasks = ScenarioLimits{}.max_tasks;
  std::vector<KeptRun> out;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const Row f = t.row(i);
    KeptRun k;
    k.line = f.line();
    RealRun& r = k.run;
    r.spec = RealCase{f.text("case"), static_cast<int>(f.whole("pipelines", 1, max_tasks)), static_cast<int>(f.whole("tasks", 1, max_tasks)),
                      bytes(f, "file_size", 1), seconds(f, "compute_s", Sign::NotNegative), bytes(f, "chunk", 1)};
    if (static_cast<std::int64_t>(r.spec.pipelines) * r.spec.tasks > max_tasks) {
      f.fail("tasks", fmt::format("{} pipelines of {} tasks are more than the {} tasks pcsim simulates", r.spec.pipelines, r.spec.tasks, max_tasks));
    }
    r.repetition = static_cast<int>(f.whole("repetition", 1, INT_MAX));
    r.makespan = seconds(f, "makespan_s", Sign::Positive);
    r.memory_total = bytes(f, "memory_total", 1);
    r.in_use_at_start = bytes(f, "in_use_at_start");
    r.free_at_start = bytes(f, "free_at_start");
    r.dropped_all_caches = f.whole("dropped_all_caches", 0, 1) != 0;
    if (t.has("others_busy_cores")) r.others_busy_cores = activity(f, "others_busy_cores", 1e6);
    if (t.has("steal_pct")) r.steal_pct = activity(f, "steal_pct", 100.0);
    if (t.has("reported_bytes")) r.reported = f.whole("reported_bytes", -1, units::kMaxBytes);
    if (t.has("warm_at_start")) r.warm_at_start = f.whole("warm_at_start", -1, units::kMaxBytes);
    out.push_back(std::move(k));
  }
  return out;
}

std::vector<KeptRow<RealPhase>> read_kept_phases(std::string_view text, const std::string& file) {
  const CsvTable t(text, file, {"case", "repetition", "pipeline", "task", "phase", "start_s", "end_s"});
  std::vector<KeptRow<RealPhase>> out;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const Row f = t.row(i);
    RealPhase p{static_cast<int>(f.whole("pipeline", 1, INT_MAX)), static_cast<int>(f.whole("task", 1, INT_MAX)),
                f.one_of("phase", {"read", "compute", "write"}), seconds(f, "start_s", Sign::NotNegative), seconds(f, "end_s", Sign::NotNegative)};
    // A read or a write takes some time: the errors are relative to it.
    if (p.end < p.start || (p.end == p.start && p.phase != "compute")) {
      f.fail("end_s", fmt::format("'{}' is not after start_s '{}': a {} phase takes some time", f.text("end_s"), f.text("start_s"), p.phase));
    }
    out.push_back({f.line(), f.text("case"), static_cast<int>(f.whole("repetition", 1, INT_MAX)), std::move(p)});
  }
  return out;
}

std::vector<KeptRow<MemorySample>> read_kept_memory(std::string_view text, const std::string& file) {
  const CsvTable t(text, file, {"case", "repetition", "time_s", "free", "cached", "dirty", "writeback"});
  std::vector<KeptRow<MemorySample>> out;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const Row f = t.row(i);
    out.push_back({f.line(), f.text("case"), static_cast<int>(f.whole("repetition", 1, INT_MAX)),
                   MemorySample{seconds(f, "time_s", Sign::NotNegative), bytes(f, "free"), bytes(f, "cached"), bytes(f, "dirty"), bytes(f, "writeback")}});
  }
  return out;
}

namespace {

// (case, repetition) -> the run's index in HereMeasurements::runs and in the rows of runs.csv.
using RunIndex = std::map<std::pair<std::string, int>, std::size_t>;
// (run, pipeline, task, phase) -> the line of phases.csv
using PhaseLines = std::map<std::tuple<std::size_t, int, int, std::string>, int>;

// Each (case, repetition) once; a case's repetitions are scored against one simulation of it,
// so they agree on what it is.
RunIndex add_runs(HereMeasurements& m, const std::vector<KeptRun>& runs, const KeptTexts& texts) {
  RunIndex index;
  std::map<std::string, const KeptRun*> first;  // a case's first repetition
  for (const KeptRun& k : runs) {
    const RealCase& c = k.run.spec;
    const auto [at, fresh] = index.emplace(std::pair{c.name, k.run.repetition}, m.runs.size());
    if (!fresh) {
      throw ConfigError(fmt::format("{}:{}: case {} repetition {} twice (also line {})", texts.runs_file, k.line, c.name, k.run.repetition,
                                    runs[at->second].line));
    }
    const auto [was, first_seen] = first.emplace(c.name, &k);
    const RealCase& f = was->second->run.spec;
    if (!first_seen && std::tie(c.pipelines, c.tasks, c.file_size, c.compute, c.chunk) != std::tie(f.pipelines, f.tasks, f.file_size, f.compute, f.chunk)) {
      throw ConfigError(fmt::format("{}:{}: case {} has other pipelines, tasks, file size, compute time or chunk than on line {}", texts.runs_file,
                                    k.line, c.name, was->second->line));
    }
    m.runs.push_back(k.run);
  }
  return index;
}

template <class T>
std::size_t run_of(const RunIndex& index, const KeptRow<T>& row, const std::string& file, const KeptTexts& texts) {
  const auto it = index.find({row.case_name, row.repetition});
  if (it == index.end()) {
    throw ConfigError(fmt::format("{}:{}: case {} repetition {} is not in {}", file, row.line, row.case_name, row.repetition, name_of(texts.runs_file)));
  }
  return it->second;
}

// Each phase within its run's pipelines and tasks, and once.
PhaseLines add_phases(HereMeasurements& m, const std::vector<KeptRow<RealPhase>>& phases, const RunIndex& index,
                      const std::vector<KeptRun>& runs, const KeptTexts& texts) {
  PhaseLines seen;
  for (const KeptRow<RealPhase>& row : phases) {
    const std::size_t i = run_of(index, row, texts.phases_file, texts);
    const RealCase& c = m.runs[i].spec;
    const RealPhase& p = row.value;
    const auto beyond = [&](const char* what, int value, int count) {
      throw ConfigError(fmt::format("{}:{}: column '{}': {} is beyond case {}'s {} {}s ({}:{})", texts.phases_file, row.line, what, value, c.name,
                                    count, what, name_of(texts.runs_file), runs[i].line));
    };
    if (p.pipeline > c.pipelines) beyond("pipeline", p.pipeline, c.pipelines);
    if (p.task > c.tasks) beyond("task", p.task, c.tasks);
    const auto [at, fresh] = seen.emplace(std::tuple{i, p.pipeline, p.task, p.phase}, row.line);
    if (!fresh) {
      throw ConfigError(fmt::format("{}:{}: the {} of pipeline {}, task {} of case {} repetition {} twice (also line {})", texts.phases_file,
                                    row.line, p.phase, p.pipeline, p.task, row.case_name, row.repetition, at->second));
    }
    m.runs[i].phases.push_back(p);
  }
  return seen;
}

void add_memory(HereMeasurements& m, const std::vector<KeptRow<MemorySample>>& memory, const RunIndex& index, const KeptTexts& texts) {
  std::vector<int> last_sample(m.runs.size(), 0);  // the line of each run's latest sample
  for (const KeptRow<MemorySample>& row : memory) {
    const std::size_t i = run_of(index, row, texts.memory_file, texts);
    RealRun& r = m.runs[i];
    // The samples of a run in time order: the real memory at an instant is the first at or after it.
    if (!r.memory.empty() && row.value.time < r.memory.back().time) {
      throw ConfigError(fmt::format("{}:{}: column 'time_s': {} is before the sample of line {} of the same run", texts.memory_file, row.line,
                                    row.value.time, last_sample[i]));
    }
    r.memory.push_back(row.value);
    last_sample[i] = row.line;
  }
}

// Rows that are needed: every phase of every run, and its memory.
void check_complete(const HereMeasurements& m, const std::vector<KeptRun>& runs, const PhaseLines& seen, const KeptTexts& texts) {
  for (std::size_t i = 0; i < m.runs.size(); ++i) {
    const RealRun& r = m.runs[i];
    const std::string run = fmt::format("{}:{}: case {} repetition {}", texts.runs_file, runs[i].line, r.spec.name, r.repetition);
    if (r.memory.empty()) throw ConfigError(fmt::format("{}: no memory sample in {}", run, name_of(texts.memory_file)));
    if (r.phases.size() == static_cast<std::size_t>(r.spec.pipelines) * static_cast<std::size_t>(r.spec.tasks) * 3) continue;
    for (int p = 1; p <= r.spec.pipelines; ++p) {
      for (int t = 1; t <= r.spec.tasks; ++t) {
        for (const char* phase : {"read", "compute", "write"}) {
          if (seen.count({i, p, t, phase}) == 0) {
            throw ConfigError(fmt::format("{}: no {} phase of pipeline {}, task {} in {}", run, phase, p, t, name_of(texts.phases_file)));
          }
        }
      }
    }
  }
}

}  // namespace

HereMeasurements parse_here(const KeptTexts& texts) {
  const std::vector<KeptRun> runs = read_kept_runs(texts.runs, texts.runs_file);
  const std::vector<KeptRow<RealPhase>> phases = read_kept_phases(texts.phases, texts.phases_file);
  const std::vector<KeptRow<MemorySample>> memory = read_kept_memory(texts.memory, texts.memory_file);
  if (runs.empty()) throw ConfigError(fmt::format("{}:1: no runs after the header", texts.runs_file));

  HereMeasurements m;
  m.platform_toml = texts.platform_toml;
  const RunIndex index = add_runs(m, runs, texts);
  const PhaseLines seen = add_phases(m, phases, index, runs, texts);
  add_memory(m, memory, index, texts);
  check_complete(m, runs, seen, texts);
  return m;
}

HereMeasurements load_here(const std::filesystem::path& folder) {
  KeptTexts t;
  const std::filesystem::path platform = folder / "platform.toml";
  std::error_code ec;
  if (!std::filesystem::exists(platform, ec)) {
    throw ConfigError(fmt::format("{}: cannot read (is {} a folder that validate --here wrote?)", platform.string(), folder.string()));
  }
  t.platform_toml = read_text_file(platform);
  t.runs_file = (folder / "runs.csv").string();
  t.phases_file = (folder / "phases.csv").string();
  t.memory_file = (folder / "memory.csv").string();
  t.runs = read_text_file(t.runs_file);
  t.phases = read_text_file(t.phases_file);
  t.memory = read_text_file(t.memory_file);
  return parse_here(t);
}

}  // namespace pagecache::validate
