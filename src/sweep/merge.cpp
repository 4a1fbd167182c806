#include "sweep/merge.hpp"

#include "report/csv_field.hpp"
#include "report/output_file.hpp"
#include "scenario/text_file.hpp"
#include "sweep/plan.hpp"
#include "sweep/result_line.hpp"
#include "sweep/results_folder.hpp"

#include <pagecache/error.hpp>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <unordered_map>
#include <vector>

namespace pagecache::sweep {

namespace {

namespace fs = std::filesystem;

struct Found {
  nlohmann::json result;
  std::string where;  // file:line
};

std::string some(const std::vector<std::string>& ids) {
  std::string out;
  for (std::size_t i = 0; i < ids.size() && i < 10; ++i) out += (i ? ", " : "") + ids[i];
  return ids.size() > 10 ? out + fmt::format(" and {} more", ids.size() - 10) : out;
}

Plan read_plan(const MergeOptions& options) {
  const fs::path plan_path = fs::path(options.dir) / "sweep-plan.json";
  if (!fs::exists(plan_path)) throw ConfigError(fmt::format("{}: no sweep-plan.json: not a folder of `pcsim sweep run --out`", options.dir));
  return Plan::from_json(scenario::read_text_file(plan_path.string(), "sweep plan"), plan_path.string());
}

// Every shard's results, whatever the sharding (shards of several splits may be merged), each
// line a result of this sweep's base. A last line cut short (a shard still running, or
// killed mid-line) is not a result: its run is not done.
std::unordered_map<std::string, Found> read_results(const MergeOptions& options, const Plan& plan) {
  std::unordered_map<std::string, Found> found;
  std::vector<std::string> duplicated;
  for_each_result(options.dir, plan.fingerprint(), [&](const std::string& id, std::string_view line, const std::string& file, std::size_t number) {
    const std::string where = fmt::format("{}:{}", file, number);
    if (const auto it = found.find(id); it != found.end()) {
      duplicated.push_back(fmt::format("{} ({} and {})", id, it->second.where, where));
      return;
    }
    found.emplace(id, Found{nlohmann::json::parse(line), where});
  });
  if (!duplicated.empty()) {
    throw ConfigError(fmt::format("{}: {} run(s) have more than one result (shards of two splits run at the same time?): {}", options.dir, duplicated.size(),
                                  some(duplicated)));
  }
  return found;
}

void append_header(fmt::memory_buffer& csv, const Plan& plan) {
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

// A run without a result, as the user finds it: its id and its overrides.
std::string missing_run(const Run& run) {
  std::string set;
  for (const Override& o : run.overrides)
    if (!o.toml.empty()) set += fmt::format("{}{}={}", set.empty() ? "" : " ", o.key, o.toml);
  return fmt::format("{} ({})", run.id, set);
}

// Results whose runs are not the plan's.
[[noreturn]] void fail_strangers(const MergeOptions& options, const Plan& plan, const std::unordered_map<std::string, Found>& found) {
  std::vector<std::string> strangers;
  std::unordered_map<std::string, bool> in_plan;
  for (std::size_t i = 0; i < plan.size(); ++i) in_plan[plan.run(i).id] = true;
  for (const auto& [id, f] : found)
    if (!in_plan.count(id)) strangers.push_back(fmt::format("{} ({})", id, f.where));
  std::sort(strangers.begin(), strangers.end());
  throw ConfigError(fmt::format("{}: {} result(s) of runs that are not in sweep-plan.json: {}", options.dir, strangers.size(), some(strangers)));
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
  const Plan plan = read_plan(options);
  const std::unordered_map<std::string, Found> found = read_results(options, plan);

  fmt::memory_buffer csv;
  append_header(csv, plan);
  std::vector<std::string> missing;
  std::size_t used = 0;
  for (std::size_t i = 0; i < plan.size(); ++i) {
    const Run run = plan.run(i);
    const auto it = found.find(run.id);
    if (it == found.end()) {
      missing.push_back(missing_run(run));
      continue;
    }
    ++used;
    if (append_row(csv, run, it->second.result) != "ok") ++outcome.failed;
    ++outcome.runs;
  }
  if (used != found.size()) fail_strangers(options, plan, found);
  outcome.missing = missing.size();
  if (!missing.empty() && !options.allow_missing) {
    throw ConfigError(fmt::format("{}: {} of {} runs have no result yet: {} (run their shards again, or --allow-missing)", options.dir,
                                  missing.size(), plan.size(), some(missing)));
  }
  report::write_output_file(outcome.csv, std::string_view(csv.data(), csv.size()), option);
  return outcome;
}

std::string results_csv(const Plan& plan, const std::vector<std::string>& lines) {
  if (lines.size() != plan.size()) throw Error(fmt::format("results_csv: {} lines for a plan of {} runs", lines.size(), plan.size()));
  fmt::memory_buffer csv;
  append_header(csv, plan);
  for (std::size_t i = 0; i < plan.size(); ++i) append_row(csv, plan.run(i), nlohmann::json::parse(lines[i]));
  return {csv.data(), csv.size()};
}

}  // namespace pagecache::sweep
