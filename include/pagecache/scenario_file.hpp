#pragma once
// Scenario files: reading a scenario (TOML, with a SimGrid or TOML platform and a WfFormat
// workflow) into the resolved Scenario of scenario.hpp, the embedded default, and writing a
// scenario back as TOML. The scenario layer's API: what runs a Scenario (the workload layer)
// needs only scenario.hpp.

#include <pagecache/scenario.hpp>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace pagecache {

/// What one scenario may ask of a run, checked when it is loaded: a typo in a count, a size, a
/// duration or a bandwidth then fails at once with a ConfigError naming the key, instead of
/// running for hours or exhausting memory. The defaults are far above what real experiments
/// need; forced() (`pcsim --force`) keeps only what pcsim cannot represent. Whatever the
/// limits, sizes are at most 1 EiB, durations 10^9 s, bandwidths 1 B/s to 1 PB/s (units.hpp).
struct ScenarioLimits {
  /// Tasks and files, pipelines expanded. A task costs a run about 2 kB (10^5 pipelines of
  /// three tasks and four files peak at 0.8 GB).
  std::int64_t max_tasks = 1'000'000;
  std::int64_t max_files = 2'000'000;
  /// Hosts, host groups expanded: each has its own page cache, flusher and devices, about
  /// 24 kB of a run (10^4 client hosts of an NFS server peak at 0.22 GB).
  std::int64_t max_hosts = 20'000;
  /// Estimated events, from every source: each chunk's transfers (each file's bytes over its
  /// task's chunk size, for every read and write) and the writeback of what is written, the
  /// pauses of writers held by dirty throttling, the flushers' and the memory sampler's
  /// wake-ups, the tasks' starts and computations. Within a factor of 3 of the events a run
  /// takes on the shipped scenarios. About ten minutes of a run at the scale of 10^5 pipelines.
  double max_events = 3e9;
  /// Estimated simulated seconds: the longest of what the busiest disk, link, memory or host's
  /// cores must move or compute, and of what the busiest application must compute and wait
  /// for the latency of the routes it crosses (paid by every transfer).
  double max_simulated_time = 1e8;
  /// Estimated memory.csv rows (held in memory until written): about 100 bytes each.
  double max_memory_rows = 2e7;

  /// Only what pcsim cannot represent: 5 * 10^8 tasks, 10^9 files, 10^9 hosts, 10^9 s.
  static ScenarioLimits forced();
};

/// Reads and resolves a scenario file (a regular file of at most 64 MiB). Its platform may be
/// a SimGrid XML file (`platform = "p.xml"`), and its workflow a WfFormat instance
/// (`workflow = "w.json"`, or a [workflow] table with `file` and options); see the README. `overrides` are
/// (dotted key, TOML value) pairs applied to the file's contents before anything is checked,
/// e.g. {"pipelines.count", "16"}; a problem with an override's value names the override.
/// `profile_override`, if set, wins over the file's `profile`. Throws ConfigError naming the
/// file, line and key of the first problem, including a scenario beyond `limits`.
Scenario load_scenario(const std::string& path, const std::vector<std::pair<std::string, std::string>>& overrides = {},
                       const std::string& profile_override = {}, const ScenarioLimits& limits = {});
/// The same from TOML text; `source_name` is used in messages.
Scenario parse_scenario(const std::string& toml_text, const std::string& source_name,
                        const std::vector<std::pair<std::string, std::string>>& overrides = {},
                        const std::string& profile_override = {}, const ScenarioLimits& limits = {});
/// What `pcsim run WORKFLOW.json --platform PLATFORM [--files-host H] [--hosts A,B]` gives
/// besides the workflow instance: the platform it runs on and, if given, where its files live
/// and where its tasks may run (empty: as the instance and the platform say; see the README).
struct WorkflowOptions {
  std::string platform;
  std::string files_host;
  std::vector<std::string> hosts;
};

/// A workflow instance (WfFormat JSON) on a platform file (SimGrid XML or TOML), read as the
/// scenario `platform = "PLATFORM"` with a [workflow] table of `file = "WORKFLOW"`,
/// `files_host` and `hosts`, so that `overrides` reach every key (workflow.chunk_size, ...).
/// A problem with an option's value names the option ("--files-host x: ..."); one of the
/// instance's own names the workflow file and its task or file. Otherwise as parse_scenario.
Scenario load_workflow(const std::string& workflow, const WorkflowOptions& options,
                       const std::vector<std::pair<std::string, std::string>>& overrides = {},
                       const std::string& profile_override = {}, const ScenarioLimits& limits = {});
/// What `pcsim run SCENARIO` (and the Python module's pcsim.run) take besides the scenario:
/// --platform, --files-host and --hosts (`workflow`), --set, --profile, and the limits.
struct RunInputs {
  WorkflowOptions workflow;
  std::vector<std::pair<std::string, std::string>> overrides;
  std::string profile;
  ScenarioLimits limits;
};
/// The scenario `pcsim run PATH` runs: a workflow instance (PATH ends in .json) on
/// inputs.workflow.platform (load_workflow); a scenario file, its `platform` key replaced by
/// inputs.workflow.platform if one is given; or, PATH empty, the embedded default. A ConfigError
/// if --files-host or --hosts come with a scenario that is not a workflow instance.
Scenario load_run_scenario(const std::string& path, const RunInputs& inputs);
/// The same for a scenario's TOML text, `source_name` naming it in messages.
Scenario parse_run_scenario(const std::string& toml_text, const std::string& source_name, const RunInputs& inputs);
/// A platform file alone (TOML, or SimGrid XML with WRENCH-cache's conventions), with every
/// route it lists (up to 10^5; Scenario::warnings says how many more), for `pcsim show`. The
/// hosts of an XML file may lack what a run needs: their memory and memory bandwidths are then
/// 0. Throws ConfigError naming the file, line and element or key at fault.
Scenario load_platform(const std::string& path, const std::string& profile_override = {});
/// The embedded default scenario (the paper's Exp 1 at 100 GB), as TOML text.
const std::string& default_scenario_text();
/// A resolved scenario as TOML, every default written out (`pcsim show`).
std::string to_toml(const Scenario& scenario);

}  // namespace pagecache
