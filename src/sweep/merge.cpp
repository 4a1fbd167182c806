#include "sweep/merge.hpp"

#include "report/csv_field.hpp"
#include "report/output_file.hpp"
#include "formats/common/text_file.hpp"
#include "sweep/sweep.hpp"
#include "sweep/result_line.hpp"
#include "sweep/results_folder.hpp"

#include <pagecache/error.hpp>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdint>
#include <optional>
#include <filesystem>
#include <unordered_map>
#include <vector>

namespace pagecache::sweep {

namespace {

namespace fs = std::filesystem;

// A result placed in the plan: its run's index and its row of results.csv.
struct Placed {
  std::size_t index = 0;
  std::string row;
};

std::string some(const std::vector<std::string>& ids, std::size_t total) {
  std::string out;
  for (std::size_t i = 0; i < ids.size() && i < 10; ++i) out += (i ? ", " : "") + ids[i];
  return total > 10 ? out + fmt::format(" and {} more", total - 10) : out;
}

Sweep read_plan(const MergeOptions& options) {
  const fs::path plan_path = fs::path(options.dir) / "sweep-plan.json";
  if (!fs::exists(plan_path)) throw ConfigError(fmt::format("{}: no sweep-plan.json: not a folder of `pcsim sweep run --out`", options.dir));
  return Sweep::from_json(formats::read_text_file(plan_path.string(), "sweep plan"), plan_path.string());
}

void append_header(fmt::memory_buffer& csv, const Sweep& plan) {
  report::append_csv_field(csv, "id");
  for (const std::string& key : plan.keys()) {
    csv.push_back(',');
    report::append_csv_field(csv, key);
  }
  csv.append(std::string_view(",status,exit_code"));
  for (const char* f : kResultFigures) fmt::format_to(std::back_inserter(csv), ",{}", f);
  csv.append(std::string_view(",error,wall_s,sim_wall_s\n"));
}

// A run's row: its id, its values, then its result's status and figures. Returns its status.
std::string append_row(fmt::memory_buffer& csv, const Run& run, const nlohmann::json& r) {
  report::append_csv_field(csv, run.id);
  for (const Override& o : run.overrides) {
    csv.push_back(',');
    report::append_csv_field(csv, o.shown);
  }
  const std::string status = r.value("status", "");
  fmt::format_to(std::back_inserter(csv), ",{},{}", status, r.value("exit_code", -1));
  for (const char* f : kResultFigures) {
    csv.push_back(',');
    if (r.contains(f)) csv.append(r[f].dump());
  }
  csv.push_back(',');
  report::append_csv_field(csv, r.value("error", ""));
  // Last, the two columns that differ from one sweep of the same runs to another.
  fmt::format_to(std::back_inserter(csv), ",{},{}\n", r.contains("wall_s") ? r["wall_s"].dump() : "", r.contains("sim_wall_s") ? r["sim_wall_s"].dump() : "");
  return status;
}

// The run a result is of: the index it was recorded under, if the plan's run there has its id
// (the same plan), else found by its overrides (a plan grown since).
std::optional<Run> run_of(const Sweep& plan, const std::string& id, const nlohmann::json& result) {
  const nlohmann::json& index = result["run"];
  if (index.is_number_unsigned() && index.get<std::uint64_t>() < plan.size()) {
    Run run = plan.run(static_cast<std::size_t>(index.get<std::uint64_t>()));
    if (run.id == id) return run;
  }
  std::vector<std::pair<std::string, std::string>> overrides;
  for (const auto& [key, value] : result["overrides"].items()) overrides.emplace_back(key, value.get<std::string>());
  const std::optional<std::size_t> at = plan.index_of(overrides);
  if (!at) return std::nullopt;
  Run run = plan.run(*at);
  if (run.id != id) return std::nullopt;
  return run;
}

// Every shard's results, whatever the sharding (shards of several splits may be merged), each
// line a result of this sweep's base, as its row, in the plan's order. Held as rows, not as
// parsed lines; the plan itself is never walked, so a plan of 10^9 runs merges its results in
// the time they take. A last line cut short (a shard still running, or killed mid-line) is
// not a result: its run is not done.
std::vector<Placed> read_results(const MergeOptions& options, const Sweep& plan, MergeOutcome& outcome) {
  std::vector<Placed> placed;
  std::unordered_map<std::string, std::string> seen;  // id -> where
  std::vector<std::string> duplicated, strangers;
  std::size_t duplicates = 0, stranger_count = 0;
  for_each_result(options.dir, plan.fingerprint(), [&](const std::string& id, std::string_view line, const std::string& file, std::size_t number) {
    std::string where = fmt::format("{}:{}", file, number);
    if (const auto it = seen.find(id); it != seen.end()) {
      if (++duplicates <= 10) duplicated.push_back(fmt::format("{} ({} and {})", id, it->second, where));
      return;
    }
    const nlohmann::json result = nlohmann::json::parse(line);
    const std::optional<Run> run = run_of(plan, id, result);
    if (!run) {
      if (++stranger_count <= 10) strangers.push_back(fmt::format("{} ({})", id, where));
      return;
    }
    seen.emplace(id, where);
    fmt::memory_buffer row;
    if (append_row(row, *run, result) != "ok") ++outcome.failed;
    placed.push_back(Placed{run->index, std::string(row.data(), row.size())});
  });
  if (duplicates > 0) {
    throw ConfigError(fmt::format("{}: {} run(s) have more than one result (shards of two splits run at the same time?): {}", options.dir, duplicates,
                                  some(duplicated, duplicates)));
  }
  if (stranger_count > 0) {
    throw ConfigError(fmt::format("{}: {} result(s) of runs that are not in sweep-plan.json: {}", options.dir, stranger_count,
                                  some(strangers, stranger_count)));
  }
  std::sort(placed.begin(), placed.end(), [](const Placed& a, const Placed& b) { return a.index < b.index; });
  return placed;
}

// A run without a result, as the user finds it: its id and its overrides.
std::string missing_run(const Run& run) {
  std::string set;
  for (const Override& o : run.overrides)
    if (!o.toml.empty()) set += fmt::format("{}{}={}", set.empty() ? "" : " ", o.key, o.toml);
  return fmt::format("{} ({})", run.id, set);
}

// The first ten runs without a result, in the plan's order: `placed` holds the others' indices.
std::vector<std::string> first_missing(const Sweep& plan, const std::vector<Placed>& placed) {
  std::vector<std::string> missing;
  auto next = placed.begin();
  for (std::size_t i = 0; i < plan.size() && missing.size() < 10; ++i) {
    while (next != placed.end() && next->index < i) ++next;
    if (next != placed.end() && next->index == i) continue;
    missing.push_back(missing_run(plan.run(i)));
  }
  return missing;
}

}  // namespace

MergeOutcome merge(const MergeOptions& options) {
  MergeOutcome outcome;
  // The user's --csv, checked before the work; the default is in the folder.
  outcome.csv = options.csv.empty() ? (fs::path(options.dir) / "results.csv").string() : options.csv;
  const std::string_view option = options.csv.empty() ? std::string_view() : std::string_view("--csv");
  report::check_output_file(outcome.csv, option);
  // Nor may it take the place of what merge reads.
  std::vector<std::string> inputs = results_files(options.dir);
  inputs.push_back((fs::path(options.dir) / "sweep-plan.json").string());
  report::check_not_an_input(outcome.csv, option, inputs);
  const Sweep plan = read_plan(options);
  const std::vector<Placed> placed = read_results(options, plan, outcome);
  outcome.runs = placed.size();
  outcome.missing = plan.size() - placed.size();
  if (outcome.missing > 0 && !options.allow_missing) {
    throw ConfigError(fmt::format("{}: {} of {} runs have no result yet: {} (run their shards again, or --allow-missing)", options.dir,
                                  outcome.missing, plan.size(), some(first_missing(plan, placed), outcome.missing)));
  }
  // Streamed: the rows as they are, a buffer's worth at a time.
  report::OutputFile csv(outcome.csv, option);
  fmt::memory_buffer buffer;
  append_header(buffer, plan);
  for (const Placed& p : placed) {
    buffer.append(p.row);
    if (buffer.size() >= (1 << 20)) {
      csv.write(std::string_view(buffer.data(), buffer.size()));
      buffer.clear();
    }
  }
  csv.write(std::string_view(buffer.data(), buffer.size()));
  csv.commit();
  return outcome;
}

std::string results_csv(const Sweep& plan, const std::vector<std::string>& lines) {
  if (lines.size() != plan.size()) throw Error(fmt::format("results_csv: {} lines for a plan of {} runs", lines.size(), plan.size()));
  fmt::memory_buffer csv;
  append_header(csv, plan);
  for (std::size_t i = 0; i < plan.size(); ++i) append_row(csv, plan.run(i), nlohmann::json::parse(lines[i]));
  return {csv.data(), csv.size()};
}

}  // namespace pagecache::sweep
