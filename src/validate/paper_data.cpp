#include "validate/paper_data.hpp"

#include "validate/csv.hpp"

#include <pagecache/error.hpp>
#include <pagecache/units.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <map>
#include <tuple>

namespace pagecache::validate {

namespace {

using Row = CsvTable::Row;

// A file size of the paper's runs, in GB, up to pcsim's largest size.
int size_gb(const Row& r) { return static_cast<int>(r.whole("file_size_gb", 1, units::kMaxBytes / 1'000'000'000)); }

double seconds(const Row& r, const char* column, Sign sign) {
  const double v = r.number(column, sign);
  if (std::abs(v) > units::kMaxSeconds) r.fail(column, fmt::format("{} s is beyond 10^9 s, the longest duration pcsim takes", v));
  return v;
}

// Bytes in `unit` bytes (MB, GB), not negative, up to pcsim's largest size (1 EiB).
double amount(const Row& r, const char* column, double unit) {
  const double v = r.number(column, Sign::NotNegative);
  if (v * unit > static_cast<double>(units::kMaxBytes)) r.fail(column, fmt::format("{} is beyond 1 EiB, the largest size pcsim takes", v));
  return v;
}

// A real read or write lasted some time: the paper's errors are relative to it.
double duration(const Row& r, bool real, const std::string& phase) {
  return seconds(r, "duration_s", real && phase != "compute" ? Sign::Positive : Sign::NotNegative);
}

template <class Key>
void once(std::map<Key, int>& seen, const Key& key, const Row& r, const std::string& file, const std::string& what) {
  const auto [it, fresh] = seen.emplace(key, r.line());
  if (!fresh) throw ConfigError(fmt::format("{}:{}: {} twice (also line {})", file, r.line(), what, it->second));
}

}  // namespace

DataFile<PhaseTime> read_exp1_phase_times(std::string_view text, const std::string& file, bool real) {
  const CsvTable t(text, file, {"file_size_gb", "task", "phase", "end_s", "duration_s"});
  DataFile<PhaseTime> out{file, {}};
  std::map<std::tuple<int, int, std::string>, int> seen;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const Row r = t.row(i);
    PhaseTime p;
    p.line = r.line();
    p.size_gb = size_gb(r);
    p.task = static_cast<int>(r.whole("task", 1, INT_MAX));
    p.phase = r.one_of("phase", {"read", "compute", "write"});
    p.end_s = seconds(r, "end_s", Sign::NotNegative);
    p.duration_s = duration(r, real, p.phase);
    once(seen, std::tuple{p.size_gb, p.task, p.phase}, r, file, fmt::format("file_size_gb {}, task {}, phase {}", p.size_gb, p.task, p.phase));
    out.rows.push_back(std::move(p));
  }
  return out;
}

DataFile<MemoryProfileRow> read_exp1_memory_profile(std::string_view text, const std::string& file) {
  const CsvTable t(text, file, {"file_size_gb", "time_s", "cached_mb", "dirty_mb", "shmem_mb"});
  DataFile<MemoryProfileRow> out{file, {}};
  for (std::size_t i = 0; i < t.size(); ++i) {
    const Row r = t.row(i);
    out.rows.push_back({r.line(), size_gb(r), seconds(r, "time_s", Sign::Any), amount(r, "cached_mb", 1e6), amount(r, "dirty_mb", 1e6),
                        amount(r, "shmem_mb", 1e6)});
  }
  return out;
}

DataFile<CachedFileRow> read_exp1_cache_contents(std::string_view text, const std::string& file) {
  const CsvTable t(text, file, {"file_size_gb", "after_task", "after_phase", "file", "cached_gb"});
  DataFile<CachedFileRow> out{file, {}};
  for (std::size_t i = 0; i < t.size(); ++i) {
    const Row r = t.row(i);
    CachedFileRow c;
    c.line = r.line();
    c.size_gb = size_gb(r);
    r.whole("after_task", 1, INT_MAX);  // matched as text with the task's name, which is its number
    c.after_task = r.text("after_task");
    c.after_phase = r.one_of("after_phase", {"read", "compute", "write"});
    c.file = r.text("file");
    c.cached_gb = amount(r, "cached_gb", 1e9);
    out.rows.push_back(std::move(c));
  }
  return out;
}

DataFile<ConcurrentPhase> read_concurrent_phase_times(std::string_view text, const std::string& file, bool real) {
  std::vector<std::string> columns = {"n_pipelines", "pipeline", "task", "phase", "duration_s"};
  if (real) columns.insert(columns.begin(), "repetition");
  const CsvTable t(text, file, columns);
  DataFile<ConcurrentPhase> out{file, {}};
  std::map<std::tuple<int, int, int, int, std::string>, int> seen;
  // Per (n, repetition), the lines of its first row, read and write: a mean needs both.
  struct Seen {
    int first = 0, read = 0, write = 0;
  };
  std::map<std::pair<int, int>, Seen> kinds;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const Row r = t.row(i);
    ConcurrentPhase p;
    p.line = r.line();
    p.repetition = real ? static_cast<int>(r.whole("repetition", 1, INT_MAX)) : 0;
    p.n = static_cast<int>(r.whole("n_pipelines", 1, INT_MAX));
    const auto pipeline = static_cast<int>(r.whole("pipeline", 1, p.n));
    const auto task = static_cast<int>(r.whole("task", 1, INT_MAX));
    p.phase = r.one_of("phase", {"read", "compute", "write"});
    p.duration_s = duration(r, real, p.phase);
    const std::string rep = real ? fmt::format("repetition {}, ", p.repetition) : "";
    once(seen, std::tuple{p.repetition, p.n, pipeline, task, p.phase}, r, file,
         fmt::format("{}n_pipelines {}, pipeline {}, task {}, phase {}", rep, p.n, pipeline, task, p.phase));
    Seen& k = kinds[{p.n, p.repetition}];
    if (k.first == 0) k.first = p.line;
    if (p.phase == "read" && k.read == 0) k.read = p.line;
    if (p.phase == "write" && k.write == 0) k.write = p.line;
    out.rows.push_back(std::move(p));
  }
  for (const auto& [key, k] : kinds) {
    if (k.read != 0 && k.write != 0) continue;
    const std::string which = real ? fmt::format("n_pipelines {}, repetition {}", key.first, key.second) : fmt::format("n_pipelines {}", key.first);
    const std::string lack = k.read != 0 ? "read rows but no write row" : k.write != 0 ? "write rows but no read row" : "no read or write row";
    throw ConfigError(fmt::format("{}:{}: {}: {}", file, k.first, which, lack));
  }
  return out;
}

PaperData read_paper_data(const std::string& dir) {
  const auto path = [&](const char* name) { return dir + "/" + name; };
  const auto text = [&](const char* name) { return read_text_file(path(name)); };
  PaperData d;
  d.exp1_real = read_exp1_phase_times(text("exp1_real_phase_times.csv"), path("exp1_real_phase_times.csv"), true);
  d.exp1_wrench = read_exp1_phase_times(text("exp1_wrench_cache_phase_times.csv"), path("exp1_wrench_cache_phase_times.csv"), false);
  d.exp1_memory = read_exp1_memory_profile(text("exp1_real_memory_profile.csv"), path("exp1_real_memory_profile.csv"));
  d.exp1_cache = read_exp1_cache_contents(text("exp1_real_cache_contents.csv"), path("exp1_real_cache_contents.csv"));
  d.exp2_real = read_concurrent_phase_times(text("exp2_real_phase_times.csv"), path("exp2_real_phase_times.csv"), true);
  d.exp2_wrench = read_concurrent_phase_times(text("exp2_wrench_cache_phase_times.csv"), path("exp2_wrench_cache_phase_times.csv"), false);
  d.exp3_real = read_concurrent_phase_times(text("exp3_real_phase_times.csv"), path("exp3_real_phase_times.csv"), true);
  d.exp3_wrench = read_concurrent_phase_times(text("exp3_wrench_cache_phase_times.csv"), path("exp3_wrench_cache_phase_times.csv"), false);
  return d;
}

}  // namespace pagecache::validate
