#include "scenario_commands.hpp"

#include <pagecache/error.hpp>
#include <pagecache/outputs.hpp>
#include <pagecache/run.hpp>
#include <pagecache/scenario.hpp>
#include <pagecache/scenario_file.hpp>

#include "report/fio_json.hpp"
#include "status_line.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cstdio>

namespace pcsim {

namespace {

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

pagecache::Scenario load(const ScenarioArgs& s) {
  pagecache::RunInputs in;
  in.workflow = {.platform = s.inputs.platform, .files_host = s.inputs.files_host, .hosts = s.inputs.hosts};
  in.overrides = parse_sets(s.sets);
  in.profile = s.profile;
  in.limits = s.force ? pagecache::ScenarioLimits::forced() : pagecache::ScenarioLimits{};
  return pagecache::load_run_scenario(s.path, in);
}

// Progress on a terminal only, for runs longer than half a second: simulated time reached and
// events per second, at most five times a second, on one line of stderr.
class Progress {
 public:
  explicit Progress(bool enabled) : line_(enabled, std::chrono::milliseconds(500)) {}
  void update(double sim_time, std::uint64_t events) {
    if (const auto wall = line_.due()) {
      line_.show(fmt::format("simulated {:.1f} s, {} events, {:.2f} M events/s", sim_time, events,
                             *wall > 0 ? static_cast<double>(events) / *wall / 1e6 : 0.0));
    }
  }
  void clear() { line_.clear(); }

 private:
  StatusLine line_;
};

void print_warnings(const pagecache::Scenario& scenario) {
  for (const std::string& warning : scenario.warnings) fmt::print(stderr, "pcsim: warning: {}\n", warning);
}

// What a run printed unless --quiet: its summary and its outputs.
void print_run(const pagecache::Scenario& named, const pagecache::RunResult& result, const pagecache::RunOutputs& outputs, const RunArgs& args) {
  fmt::print("{}", pagecache::readable_summary(named, result));
  if (!named.fio.jobs.empty()) fmt::print("{}", pagecache::report::fio_summary(named, result));
  const std::string extra = std::string(!args.no_report ? ", report.html" : "") + (outputs.writes_trace() ? ", trace.json" : "") +
                            (named.fio.jobs.empty() ? "" : ", fio.json");
  if (result.cache_not_recorded.empty()) {
    fmt::print("outputs: {}/{{timeline.csv, memory.csv, cache.csv, summary.json, timing.json{}}}\n", args.out_dir, extra);
  } else {
    fmt::print("outputs: {}/{{timeline.csv, memory.csv, summary.json, timing.json{}}}; cache contents {}\n", args.out_dir, extra,
               pagecache::cache_contents_note(result));
  }
}

}  // namespace

Overrides parse_sets(const std::vector<std::string>& sets) {
  Overrides out;
  for (const std::string& s : sets) {
    const auto eq = s.find('=');
    if (eq == std::string::npos || eq == 0) {
      throw pagecache::ConfigError(fmt::format("--set '{}': expected KEY=VALUE, e.g. --set pipelines.count=16", s));
    }
    out.emplace_back(s.substr(0, eq), s.substr(eq + 1));
  }
  return out;
}

int run_command(const ScenarioArgs& s, const RunArgs& args) {
  pagecache::Scenario scenario = load(s);
  if (!args.quiet) print_warnings(scenario);
  pagecache::check_output_folder(args.out_dir, s.path);  // before simulating, not after
  Progress progress(!args.quiet);
  pagecache::RunOptions options;
  options.cache_contents = !args.no_cache_contents;
  options.progress = [&progress](double t, std::uint64_t events) { progress.update(t, events); };
  // The same outputs as an embedding program writes (pagecache/outputs.hpp).
  pagecache::RunOutputs outputs({.report = !args.no_report, .trace = args.trace || scenario.trace});
  outputs.attach(options);
  // The outputs name the scenario (its file, title and profile); the run takes the rest and
  // frees its applications and files once planned (at 10^5 applications, a large share of its memory).
  pagecache::Scenario named;
  named.source = scenario.source;
  named.title = scenario.title;
  named.profile = scenario.profile;
  named.fio = scenario.fio;  // fio.json's jobs
  pagecache::RunResult result;
  try {
    result = pagecache::run_scenario(std::move(scenario), options);
  } catch (...) {
    progress.clear();
    throw;
  }
  progress.clear();
  const std::vector<std::string> warnings = outputs.write(args.out_dir, named, result);
  if (outputs.trace_truncated()) {
    fmt::print(stderr, "pcsim: warning: trace.json holds every phase and memory row, but transfers, flushes, evictions and pauses "
                       "only up to its first GB\n");
  }
  for (const std::string& warning : warnings) fmt::print(stderr, "pcsim: warning: {}\n", warning);
  if (!args.quiet) print_run(named, result, outputs, args);
  return 0;
}

int show_command(const ScenarioArgs& s) {
  // A platform alone: an XML file, or --platform without a scenario.
  const bool platform_alone = ends_with(s.path, ".xml") || (s.path.empty() && !s.inputs.platform.empty());
  if (platform_alone && !s.sets.empty()) throw pagecache::ConfigError("--set changes a scenario; a platform is shown as its file says");
  const pagecache::Scenario scenario =
      platform_alone ? pagecache::load_platform(s.path.empty() ? s.inputs.platform : s.path, s.profile) : load(s);
  print_warnings(scenario);
  fmt::print("{}", pagecache::to_toml(scenario));
  return 0;
}

}  // namespace pcsim
