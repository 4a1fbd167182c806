// pcsim: the command line. Thin: parse the arguments, load the scenario, run it, report.
//
// Exit codes: 0 success; 1 the simulation could not proceed (SimulationError); 2 bad input
// (scenario, --set, options, a path given that the file system refuses, an output the option
// names that cannot be written); 3 an internal invariant broke or memory ran out.

#include <pagecache/error.hpp>
#include <pagecache/version.hpp>

#include "report/interrupt_cleanup.hpp"
#include "report/output_file.hpp"
#include "formats/common/closest.hpp"
#include "text/path_problem.hpp"
#include "validate/switches.hpp"
#include "validate/validation.hpp"
#include "calibrate_command.hpp"
#include "data_dir.hpp"
#include "scenario_commands.hpp"
#include "sweep_command.hpp"
#include "validate_here_command.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <new>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

const char* const kForceHelp = "load a scenario beyond the limits on its size, events, simulated time and memory profile "
                               "(what pcsim cannot represent is still refused)";
const char* const kPlatformHelp = "platform file, SimGrid XML (WRENCH-cache's conventions) or TOML: what a workflow file runs on, or "
                                  "in place of a scenario's own";
const char* const kFilesHostHelp = "host whose disk stores a workflow file's files (default: the first of its recorded machines the "
                                   "platform has, else the first of --hosts, else the platform's first host)";
const char* const kHostsHelp = "hosts a workflow file's tasks may run on, besides those its recorded machines name (default: those "
                               "machines, else with --files-host every other host, else the files host)";

// `pcsim validate` without --here or --from: the paper's experiments against the real runs.
struct ValidateCommand {
  CLI::App* app = nullptr;
  std::string json_path;
  std::string report_path = "validate-report.html";
  std::string profile = "linux";
  std::vector<std::string> switches;
  std::string data_dir;
  std::string scenarios_dir;
  pcsim::ValidateHereOptions here;
};

// Every command and option of pcsim, and where each lands once parsed. `run`, `show` and
// `validate` share the scenario's --set: only one of them is parsed.
struct CommandLine {
  CLI::App app{"pcsim: a discrete-event simulator of the Linux page cache"};
  pcsim::ScenarioArgs scenario;
  pcsim::RunArgs run_args;
  CLI::App* run = nullptr;
  CLI::App* show = nullptr;
  ValidateCommand validate;
  pcsim::SweepCommand sweep;
  pcsim::CalibrateCommand calibrate;
  CLI::App* help = nullptr;
  std::string help_topic;
  std::vector<std::string> commands;  // their names, in order
};

void add_run_command(CommandLine& c) {
  c.run = c.app.add_subcommand("run", "run a scenario or a workflow (without either: the embedded default, the paper's Exp 1 at 100 GB)");
  CLI::App& run = *c.run;
  run.add_option("scenario", c.scenario.path, "scenario file (TOML), or workflow file (WfFormat JSON, with --platform)");
  run.add_option("--platform", c.scenario.inputs.platform, kPlatformHelp);
  run.add_option("--files-host", c.scenario.inputs.files_host, kFilesHostHelp);
  run.add_option("--hosts", c.scenario.inputs.hosts, kHostsHelp)->delimiter(',');
  run.add_option("--out", c.run_args.out_dir,
                 "output folder: made if absent; an empty folder or one an earlier run made (marked by .pcsim-output) "
                 "is replaced whole; anything else is refused and left untouched")
      ->capture_default_str();
  run.add_option("--profile", c.scenario.profile, "model profile, overriding the scenario's")->check(CLI::IsMember({"paper", "linux"}));
  run.add_option("--set", c.scenario.sets, "override a scenario key: KEY=VALUE (repeatable), e.g. pipelines.count=16");
  run.add_flag("--quiet", c.run_args.quiet, "print nothing but errors");
  run.add_flag("--no-cache-contents", c.run_args.no_cache_contents, "do not record cache.csv (large workloads)");
  run.add_flag("--force", c.scenario.force, kForceHelp);
  run.add_flag("--no-report", c.run_args.no_report, "do not write report.html (the run's figures drawn in one offline page)");
  run.add_flag("--trace", c.run_args.trace,
               "also write trace.json (Chrome Trace Event format: open it in ui.perfetto.dev or chrome://tracing); the scenario key "
               "trace = true does the same");
}

void add_show_command(CommandLine& c) {
  c.show = c.app.add_subcommand("show", "print the fully resolved scenario, defaults included, or a platform file alone");
  CLI::App& show = *c.show;
  show.add_option("scenario", c.scenario.path,
                  "scenario file (TOML), workflow file (JSON, with --platform) or platform file (XML); the embedded default if omitted");
  show.add_option("--platform", c.scenario.inputs.platform, std::string(kPlatformHelp) + "; alone, the platform is shown");
  show.add_option("--files-host", c.scenario.inputs.files_host, kFilesHostHelp);
  show.add_option("--hosts", c.scenario.inputs.hosts, kHostsHelp)->delimiter(',');
  show.add_option("--profile", c.scenario.profile, "model profile, overriding the scenario's")->check(CLI::IsMember({"paper", "linux"}));
  show.add_option("--set", c.scenario.sets, "override a scenario key: KEY=VALUE (repeatable)");
  show.add_flag("--force", c.scenario.force, kForceHelp);
}

void add_validate_command(CommandLine& c) {
  ValidateCommand& v = c.validate;
  v.app = c.app.add_subcommand("validate", "compare the paper's experiments with the real measurements");
  // The shipped data beside this pcsim (data_dir.hpp); a pcsim without it needs both options.
  const std::filesystem::path shipped = pcsim::data_dir();
  v.data_dir = shipped.empty() ? std::string() : (shipped / "validation" / "paper").string();
  v.scenarios_dir = shipped.empty() ? std::string() : (shipped / "scenarios" / "paper").string();
  v.app->add_option("--json", v.json_path, "also write the results as JSON to this file");
  v.app->add_option("--report", v.report_path, "write the results as a self-contained HTML page to this file")->capture_default_str();
  v.app->add_option("--profile", v.profile, "model profile (the paper scenarios' own profile is paper)")
      ->check(CLI::IsMember({"paper", "linux"}))
      ->capture_default_str();
  v.app->add_option("--set", c.scenario.sets, "override a key of every scenario: KEY=VALUE (repeatable)");
  v.app->add_option("--switch", v.switches, "force a page-cache switch on every host: NAME=true|false (ablations)");
  v.app->add_option("--data", v.data_dir, "the validation data")->capture_default_str();
  v.app->add_option("--scenarios", v.scenarios_dir, "the paper's scenarios")->capture_default_str();
  pcsim::add_validate_here_options(*v.app, v.here);
}

// `help`, last: it names every command before it.
void add_help_command(CommandLine& c) {
  c.help = c.app.add_subcommand("help", "show this help, or a command's: pcsim help run");
  for (const CLI::App* sub : c.app.get_subcommands({})) c.commands.push_back(sub->get_name());
  c.help->add_option("command", c.help_topic, "the command to explain")->check(CLI::IsMember(c.commands));
}

void build_command_line(CommandLine& c) {
  c.app.set_version_flag("--version", std::string("pcsim ") + pagecache::kVersion);
  c.app.require_subcommand(1);
  add_run_command(c);
  add_show_command(c);
  add_validate_command(c);
  pcsim::add_sweep_command(c.app, c.sweep);
  pcsim::add_calibrate_command(c.app, c.calibrate);
  add_help_command(c);
}

// The command a user typed that pcsim does not know, with the closest it knows: CLI11 only
// says an argument was not expected.
int unknown_command(const std::string& typed, const std::vector<std::string>& commands) {
  std::string list;
  for (const std::string& c : commands) list += (list.empty() ? "" : ", ") + c;
  const std::string meant = pagecache::formats::closest(typed, {commands.begin(), commands.end()});
  fmt::print(stderr, "pcsim: unknown command '{}'{} (commands: {}; pcsim help lists them)\n", typed,
             meant.empty() ? std::string() : fmt::format(", did you mean '{}'?", meant), list);
  return 2;
}

// Parses the arguments into `c`: the exit code if that is all (help, version, a mistake).
std::optional<int> parse_command_line(CommandLine& c, int argc, char** argv) {
  if (argc > 1 && argv[1][0] != '-' && std::find(c.commands.begin(), c.commands.end(), argv[1]) == c.commands.end()) {
    return unknown_command(argv[1], c.commands);
  }
  try {
    c.app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return c.app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return c.app.exit(e);
  } catch (const CLI::ParseError& e) {
    c.app.exit(e);
    return 2;
  }
  return std::nullopt;
}

int help_command(const CommandLine& c) {
  // The formatter, not app.help(), which would explain the help command itself.
  const CLI::App* topic = c.help_topic.empty() ? &c.app : c.app.get_subcommand(c.help_topic);
  fmt::print("{}", c.app.get_formatter()->make_help(topic, c.help_topic.empty() ? "pcsim" : "pcsim " + c.help_topic, CLI::AppFormatMode::Normal));
  return 0;
}

// Two names of one regular file (or of one file to be made); devices and FIFOs may take both.
bool same_regular_file(const std::string& a, const std::string& b) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status sa = fs::status(a, ec), sb = fs::status(b, ec);
  if (fs::exists(sa) && fs::exists(sb)) return fs::is_regular_file(sa) && fs::equivalent(a, b, ec);
  return fs::weakly_canonical(a, ec) == fs::weakly_canonical(b, ec);
}

// The regular files directly in these folders.
std::vector<std::string> files_in(std::initializer_list<std::string> folders) {
  std::vector<std::string> files;
  std::error_code ec;
  for (const std::string& folder : folders) {
    for (std::filesystem::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
      if (it->is_regular_file(ec)) files.push_back(it->path().string());
    }
  }
  return files;
}

int validate_command(const ValidateCommand& v, const std::vector<std::string>& sets) {
  // The command line's own mistakes first: they need no data to be seen.
  const bool write_json = v.app->count("--json") > 0;  // `--json ''` is refused, not ignored
  if (write_json) pagecache::report::check_output_file(v.json_path, "--json");
  pagecache::report::check_output_file(v.report_path, "--report");
  if (write_json && same_regular_file(v.json_path, v.report_path)) {
    throw pagecache::ConfigError(fmt::format("--report {}: is --json's file too; name two files", v.report_path));
  }
  if (v.data_dir.empty() || v.scenarios_dir.empty()) {
    throw pagecache::ConfigError(fmt::format("validate: no validation data beside this pcsim (looked in {}): give --data FOLDER and "
                                             "--scenarios FOLDER (validation/paper and scenarios/paper of pcsim's sources)",
                                             pcsim::data_dir_looked_at().string()));
  }
  // Nor may an output take the place of the data or the scenarios validate reads.
  const std::vector<std::string> inputs = files_in({v.data_dir, v.scenarios_dir});
  if (write_json) pagecache::report::check_not_an_input(v.json_path, "--json", inputs);
  pagecache::report::check_not_an_input(v.report_path, "--report", inputs);
  const auto forced = pagecache::validate::parse_switches(v.switches);
  const auto report = pagecache::validate::run({v.data_dir, v.scenarios_dir, v.profile, pcsim::parse_sets(sets), forced});
  fmt::print("{}", report.text());
  if (write_json) pagecache::report::write_output_file(v.json_path, report.json(), "--json");
  pagecache::report::write_output_file(v.report_path, report.html(), "--report");
  fmt::print("report: {}\n", v.report_path);
  return 0;
}

// Runs the command that was parsed.
int dispatch(CommandLine& c) {
  if (c.help->parsed()) return help_command(c);
  if (c.sweep.sweep->parsed()) return pcsim::run_sweep_command(c.sweep);
  if (c.calibrate.app->parsed()) return pcsim::run_calibrate_command(c.calibrate);
  const pcsim::ValidateHereOptions& here = c.validate.here;
  if (c.validate.app->parsed()) pcsim::check_validate_mode(*c.validate.app);
  if (c.validate.app->parsed() && (here.here || !here.from.empty())) return pcsim::run_validate_here(here);
  if (c.validate.app->parsed()) return validate_command(c.validate, c.scenario.sets);
  if (c.show->parsed()) return pcsim::show_command(c.scenario);
  return pcsim::run_command(c.scenario, c.run_args);
}

// The parsed command's exit code: its own, or the documented one of the error that stopped it.
int run_parsed_command(CommandLine& c) {
  // What helps when memory runs out depends on the command: a run's outputs, or nothing.
  const bool simulating = c.run->parsed();
  try {
    return dispatch(c);
  } catch (const pagecache::ConfigError& e) {
    fmt::print(stderr, "pcsim: {}\n", e.what());
    return 2;
  } catch (const std::filesystem::filesystem_error& e) {
    // A path given that the file system refused, where no reader named its option: the path.
    fmt::print(stderr, "pcsim: {}\n", pagecache::text::path_message({}, e.path1().string(), e.code().message()));
    return 2;
  } catch (const pagecache::SimulationError& e) {
    fmt::print(stderr, "pcsim: simulation failed: {}\n", e.what());
    return 1;
  } catch (const pagecache::InvariantError& e) {
    fmt::print(stderr, "pcsim: internal error (please report): {}\n", e.what());
    return 3;
  } catch (const std::bad_alloc&) {
    fmt::print(stderr, "pcsim: out of memory{}\n", simulating ? " (a smaller scenario, or --no-cache-contents, needs less)" : "");
    return 3;
  } catch (const std::length_error& e) {
    fmt::print(stderr, "pcsim: out of memory ({})\n", e.what());
    return 3;
  } catch (const std::exception& e) {
    fmt::print(stderr, "pcsim: {}\n", e.what());
    return 1;
  }
}

}  // namespace

int main(int argc, char** argv) {
  // Ctrl-C, kill or a closed terminal while an output is written: its staging folder or
  // temporary file goes too (exit 130, 143 or 129).
  pagecache::report::install_interrupt_cleanup();
  CommandLine command_line;
  build_command_line(command_line);
  if (const std::optional<int> done = parse_command_line(command_line, argc, argv)) return *done;
  return run_parsed_command(command_line);
}
