#pragma once
// `pcsim run` and `pcsim show`: a scenario file, the embedded default or a workflow file on a
// platform, loaded with the command line's overrides, then run with its outputs written, or
// printed resolved.

#include <string>
#include <utility>
#include <vector>

namespace pcsim {

using Overrides = std::vector<std::pair<std::string, std::string>>;

/// `--set KEY=VALUE` options as overrides; ConfigError for one without KEY=.
Overrides parse_sets(const std::vector<std::string>& sets);

/// What the command line gives besides a scenario: a platform, and for a workflow instance
/// where its files live and where its tasks may run.
struct Inputs {
  std::string platform;
  std::string files_host;
  std::vector<std::string> hosts;
};

/// What `run` and `show` load.
struct ScenarioArgs {
  std::string path;  ///< a scenario or workflow file (a platform file for show); empty: the embedded default
  Inputs inputs;
  std::vector<std::string> sets;
  std::string profile;  ///< empty: the scenario's own
  bool force = false;   ///< beyond the limits on a scenario's size
};

/// How `run` writes and prints.
struct RunArgs {
  std::string out_dir = "pcsim-out";
  bool quiet = false;
  bool no_cache_contents = false;
  bool trace = false;
  bool no_report = false;
};

/// `pcsim run`, `pcsim show`. Throw as the library does (main maps errors to exit codes);
/// return the exit code otherwise.
int run_command(const ScenarioArgs& scenario, const RunArgs& args);
int show_command(const ScenarioArgs& scenario);

}  // namespace pcsim
