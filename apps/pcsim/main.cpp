// pcsim: the command line. Thin: parse the arguments, load the scenario, run it, report.
//
// Exit codes: 0 success; 1 the simulation could not proceed (SimulationError) or an output
// could not be written; 2 bad input (scenario, --set, options); 3 an internal invariant broke
// or memory ran out.

#include <pagecache/error.hpp>
#include <pagecache/outputs.hpp>
#include <pagecache/run.hpp>
#include <pagecache/scenario.hpp>
#include <pagecache/scenario_file.hpp>
#include <pagecache/version.hpp>

#include "report/interrupt_cleanup.hpp"
#include "report/output_file.hpp"
#include "scenario/closest.hpp"
#include "validate/switches.hpp"
#include "validate/validation.hpp"
#include "calibrate_command.hpp"
#include "data_dir.hpp"
#include "status_line.hpp"
#include "sweep_command.hpp"
#include "validate_here_command.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <toml++/toml.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <new>
#include <optional>
#include <stdexcept>
#include <string>
#include <unistd.h>
#include <utility>
#include <vector>

namespace {

using Overrides = std::vector<std::pair<std::string, std::string>>;

// `text` as a TOML string (for --set: a value is read as TOML).
std::string toml_string(const std::string& text) {
  std::ostringstream out;
  out << toml::value<std::string>(text);
  return out.str();
}

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

// What the command line gives besides a scenario: a platform, and for a workflow instance
// where its files live and where its tasks may run.
struct Inputs {
  std::string platform;
  std::string files_host;
  std::vector<std::string> hosts;
};

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

std::string absolute(const std::string& path) { return std::filesystem::absolute(path).lexically_normal().string(); }

// A workflow instance (WfFormat JSON) on a platform file (pagecache::load_workflow): --set
// reaches every key, and a problem with an option names it.
pagecache::Scenario load_workflow(const std::string& path, const Inputs& in, const std::vector<std::string>& sets, const std::string& profile,
                                  const pagecache::ScenarioLimits& limits) {
  pagecache::WorkflowOptions options;
  options.platform = in.platform;
  options.files_host = in.files_host;
  options.hosts = in.hosts;
  return pagecache::load_workflow(path, options, parse_sets(sets), profile, limits);
}

pagecache::Scenario load(const std::string& path, const Inputs& in, const std::vector<std::string>& sets, const std::string& profile, bool force) {
  const pagecache::ScenarioLimits limits = force ? pagecache::ScenarioLimits::forced() : pagecache::ScenarioLimits{};
  if (ends_with(path, ".json")) return load_workflow(path, in, sets, profile, limits);
  if (!in.files_host.empty() || !in.hosts.empty()) {
    throw pagecache::ConfigError("--files-host and --hosts place a workflow file's (JSON) files and tasks; a scenario gives them in its [workflow] table");
  }
  Overrides overrides = parse_sets(sets);
  // A scenario on another platform: --platform is its `platform` key.
  if (!in.platform.empty()) overrides.insert(overrides.begin(), {"platform", toml_string(absolute(in.platform))});
  if (path.empty()) {
    return pagecache::parse_scenario(pagecache::default_scenario_text(), "<embedded default>", overrides, profile, limits);
  }
  return pagecache::load_scenario(path, overrides, profile, limits);
}

// The command a user typed that pcsim does not know, with the closest it knows: CLI11 only
// says an argument was not expected.
int unknown_command(const std::string& typed, const std::vector<std::string>& commands) {
  std::string list;
  for (const std::string& c : commands) list += (list.empty() ? "" : ", ") + c;
  const std::string meant = pagecache::scenario::closest(typed, {commands.begin(), commands.end()});
  fmt::print(stderr, "pcsim: unknown command '{}'{} (commands: {}; pcsim help lists them)\n", typed,
             meant.empty() ? std::string() : fmt::format(", did you mean '{}'?", meant), list);
  return 2;
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
  pcsim::StatusLine line_;
};

void print_warnings(const pagecache::Scenario& scenario) {
  for (const std::string& warning : scenario.warnings) fmt::print(stderr, "pcsim: warning: {}\n", warning);
}

int run_command(const std::string& path, const Inputs& in, const std::vector<std::string>& sets, const std::string& profile,
                const std::string& out_dir, bool quiet, bool cache_contents, bool force, bool trace, bool report) {
  pagecache::Scenario scenario = load(path, in, sets, profile, force);
  if (!quiet) print_warnings(scenario);
  pagecache::check_output_folder(out_dir, path);  // before simulating, not after
  Progress progress(!quiet);
  pagecache::RunOptions options;
  options.cache_contents = cache_contents;
  options.progress = [&progress](double t, std::uint64_t events) { progress.update(t, events); };
  // The same outputs as an embedding program writes (pagecache/outputs.hpp).
  pagecache::RunOutputs outputs({.report = report, .trace = trace || scenario.trace});
  outputs.attach(options);
  // The outputs name the scenario (its file, title and profile); the run takes the rest and
  // frees its applications and files once planned (at 10^5 applications, a fifth of its memory).
  pagecache::Scenario named;
  named.source = scenario.source;
  named.title = scenario.title;
  named.profile = scenario.profile;
  pagecache::RunResult result;
  try {
    result = pagecache::run_scenario(std::move(scenario), options);
  } catch (...) {
    progress.clear();
    throw;
  }
  progress.clear();
  const std::vector<std::string> warnings = outputs.write(out_dir, named, result);
  if (outputs.trace_truncated()) {
    fmt::print(stderr, "pcsim: warning: trace.json holds every phase and memory row, but transfers, flushes, evictions and pauses "
                       "only up to its first GB\n");
  }
  for (const std::string& warning : warnings) fmt::print(stderr, "pcsim: warning: {}\n", warning);
  if (!quiet) {
    fmt::print("{}", pagecache::readable_summary(named, result));
    const std::string extra = std::string(report ? ", report.html" : "") + (outputs.writes_trace() ? ", trace.json" : "");
    if (result.cache_not_recorded.empty()) {
      fmt::print("outputs: {}/{{timeline.csv, memory.csv, cache.csv, summary.json, timing.json{}}}\n", out_dir, extra);
    } else {
      fmt::print("outputs: {}/{{timeline.csv, memory.csv, summary.json, timing.json{}}}; cache contents {}\n", out_dir, extra,
                 pagecache::cache_contents_note(result));
    }
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  // Ctrl-C, kill or a closed terminal while an output is written: its staging folder or
  // temporary file goes too (exit 130, 143 or 129).
  pagecache::report::install_interrupt_cleanup();
  CLI::App app{"pcsim: a discrete-event simulator of the Linux page cache"};
  app.set_version_flag("--version", std::string("pcsim ") + pagecache::kVersion);
  app.require_subcommand(1);

  std::string scenario_path;
  std::string out_dir = "pcsim-out";
  std::string profile;
  std::vector<std::string> sets;
  bool quiet = false;
  bool no_cache_contents = false;
  bool force = false;
  const char* force_help = "load a scenario beyond the limits on its size, events, simulated time and memory profile "
                           "(what pcsim cannot represent is still refused)";

  Inputs inputs;
  const char* platform_help = "platform file, SimGrid XML (WRENCH-cache's conventions) or TOML: what a workflow file runs on, or "
                              "in place of a scenario's own";
  const char* files_host_help = "host whose disk stores a workflow file's files (default: the first of its recorded machines the "
                                "platform has, else the first of --hosts, else the platform's first host)";
  const char* hosts_help = "hosts a workflow file's tasks may run on, besides those its recorded machines name (default: those "
                           "machines, else with --files-host every other host, else the files host)";
  auto* run = app.add_subcommand("run", "run a scenario or a workflow (without either: the embedded default, the paper's Exp 1 at 100 GB)");
  run->add_option("scenario", scenario_path, "scenario file (TOML), or workflow file (WfFormat JSON, with --platform)");
  run->add_option("--platform", inputs.platform, platform_help);
  run->add_option("--files-host", inputs.files_host, files_host_help);
  run->add_option("--hosts", inputs.hosts, hosts_help)->delimiter(',');
  run->add_option("--out", out_dir,
                  "output folder: made if absent; an empty folder or one an earlier run made (marked by .pcsim-output) "
                  "is replaced whole; anything else is refused and left untouched")
      ->capture_default_str();
  run->add_option("--profile", profile, "model profile, overriding the scenario's")->check(CLI::IsMember({"paper", "linux"}));
  run->add_option("--set", sets, "override a scenario key: KEY=VALUE (repeatable), e.g. pipelines.count=16");
  run->add_flag("--quiet", quiet, "print nothing but errors");
  run->add_flag("--no-cache-contents", no_cache_contents, "do not record cache.csv (large workloads)");
  run->add_flag("--force", force, force_help);
  bool no_report = false;
  run->add_flag("--no-report", no_report, "do not write report.html (the run's figures drawn in one offline page)");
  bool trace = false;
  run->add_flag("--trace", trace,
                "also write trace.json (Chrome Trace Event format: open it in ui.perfetto.dev or chrome://tracing); the scenario key "
                "trace = true does the same");

  auto* show = app.add_subcommand("show", "print the fully resolved scenario, defaults included, or a platform file alone");
  show->add_option("scenario", scenario_path,
                   "scenario file (TOML), workflow file (JSON, with --platform) or platform file (XML); the embedded default if omitted");
  show->add_option("--platform", inputs.platform, std::string(platform_help) + "; alone, the platform is shown");
  show->add_option("--files-host", inputs.files_host, files_host_help);
  show->add_option("--hosts", inputs.hosts, hosts_help)->delimiter(',');
  show->add_option("--profile", profile, "model profile, overriding the scenario's")->check(CLI::IsMember({"paper", "linux"}));
  show->add_option("--set", sets, "override a scenario key: KEY=VALUE (repeatable)");
  show->add_flag("--force", force, force_help);

  auto* validate = app.add_subcommand("validate", "compare the paper's experiments with the real measurements");
  std::string json_path;
  // The shipped data beside this pcsim (data_dir.hpp); a pcsim without it needs both options.
  const std::filesystem::path shipped = pcsim::data_dir();
  std::string data_dir = shipped.empty() ? std::string() : (shipped / "validation" / "paper").string();
  std::string scenarios_dir = shipped.empty() ? std::string() : (shipped / "scenarios" / "paper").string();
  validate->add_option("--json", json_path, "also write the results as JSON to this file");
  std::string report_path = "validate-report.html";
  validate->add_option("--report", report_path, "write the results as a self-contained HTML page to this file")->capture_default_str();
  std::string validate_profile = "linux";
  validate->add_option("--profile", validate_profile, "model profile (the paper scenarios' own profile is paper)")
      ->check(CLI::IsMember({"paper", "linux"}))
      ->capture_default_str();
  validate->add_option("--set", sets, "override a key of every scenario: KEY=VALUE (repeatable)");
  std::vector<std::string> switches;
  validate->add_option("--switch", switches, "force a page-cache switch on every host: NAME=true|false (ablations)");
  validate->add_option("--data", data_dir, "the validation data")->capture_default_str();
  validate->add_option("--scenarios", scenarios_dir, "the paper's scenarios")->capture_default_str();
  pcsim::ValidateHereOptions here;
  pcsim::add_validate_here_options(*validate, here);

  pcsim::SweepCommand sweep;
  pcsim::add_sweep_command(app, sweep);
  pcsim::CalibrateCommand calibrate;
  pcsim::add_calibrate_command(app, calibrate);

  auto* help = app.add_subcommand("help", "show this help, or a command's: pcsim help run");
  std::string help_topic;
  std::vector<std::string> commands;
  for (const CLI::App* sub : app.get_subcommands({})) commands.push_back(sub->get_name());
  help->add_option("command", help_topic, "the command to explain")->check(CLI::IsMember(commands));

  if (argc > 1 && argv[1][0] != '-' && std::find(commands.begin(), commands.end(), argv[1]) == commands.end()) {
    return unknown_command(argv[1], commands);
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return 2;
  }

  try {
    if (help->parsed()) {
      // The formatter, not app.help(), which would explain the help command itself.
      const CLI::App* topic = help_topic.empty() ? &app : app.get_subcommand(help_topic);
      fmt::print("{}", app.get_formatter()->make_help(topic, help_topic.empty() ? "pcsim" : "pcsim " + help_topic, CLI::AppFormatMode::Normal));
      return 0;
    }
    if (sweep.sweep->parsed()) return pcsim::run_sweep_command(sweep);
    if (calibrate.app->parsed()) return pcsim::run_calibrate_command(calibrate);
    if (validate->parsed() && (here.here || !here.from.empty())) return pcsim::run_validate_here(here);
    if (validate->parsed()) {
      // The command line's own mistakes first: they need no data to be seen.
      const bool write_json = validate->count("--json") > 0;  // `--json ''` is refused, not ignored
      if (write_json) pagecache::report::check_output_file(json_path, "--json");
      pagecache::report::check_output_file(report_path, "--report");
      if (data_dir.empty() || scenarios_dir.empty()) {
        throw pagecache::ConfigError(fmt::format("validate: no validation data beside this pcsim (looked in {}): give --data FOLDER and "
                                                 "--scenarios FOLDER (validation/paper and scenarios/paper of pcsim's sources)",
                                                 pcsim::data_dir_looked_at().string()));
      }
      const auto forced = pagecache::validate::parse_switches(switches);
      const auto report = pagecache::validate::run({data_dir, scenarios_dir, validate_profile, parse_sets(sets), forced});
      fmt::print("{}", report.text());
      if (write_json) pagecache::report::write_output_file(json_path, report.json(), "--json");
      pagecache::report::write_output_file(report_path, report.html(), "--report");
      fmt::print("report: {}\n", report_path);
      return 0;
    }
    if (show->parsed()) {
      // A platform alone: an XML file, or --platform without a scenario.
      const bool platform_alone = ends_with(scenario_path, ".xml") || (scenario_path.empty() && !inputs.platform.empty());
      if (platform_alone && !sets.empty()) throw pagecache::ConfigError("--set changes a scenario; a platform is shown as its file says");
      const pagecache::Scenario scenario = platform_alone ? pagecache::load_platform(scenario_path.empty() ? inputs.platform : scenario_path, profile)
                                                          : load(scenario_path, inputs, sets, profile, force);
      print_warnings(scenario);
      fmt::print("{}", pagecache::to_toml(scenario));
      return 0;
    }
    return run_command(scenario_path, inputs, sets, profile, out_dir, quiet, !no_cache_contents, force, trace, !no_report);
  } catch (const pagecache::ConfigError& e) {
    fmt::print(stderr, "pcsim: {}\n", e.what());
    return 2;
  } catch (const pagecache::SimulationError& e) {
    fmt::print(stderr, "pcsim: simulation failed: {}\n", e.what());
    return 1;
  } catch (const pagecache::InvariantError& e) {
    fmt::print(stderr, "pcsim: internal error (please report): {}\n", e.what());
    return 3;
  } catch (const std::bad_alloc&) {
    fmt::print(stderr, "pcsim: out of memory (a smaller scenario, or --no-cache-contents, needs less)\n");
    return 3;
  } catch (const std::length_error& e) {
    fmt::print(stderr, "pcsim: out of memory ({})\n", e.what());
    return 3;
  } catch (const std::exception& e) {
    fmt::print(stderr, "pcsim: {}\n", e.what());
    return 1;
  }
}
