#pragma once
// Scenario: everything one simulation run needs — the platform (hosts, their memory, disks
// and page-cache settings), the files, and the workload — fully resolved (units converted,
// defaults filled, shorthands expanded). Loaded from a TOML file by load_scenario(); see the
// README for the format. Run by run_scenario() (pagecache/run.hpp).

#include <pagecache/cache_settings.hpp>
#include <pagecache/devices.hpp>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace pagecache {

/// A model profile: `paper` reproduces WRENCH-cache (the paper's simulator); `linux`
/// follows the kernel.
enum class Profile { Paper, Linux };

const char* to_string(Profile profile);
CacheSettings settings_for(Profile profile);
/// The switches of CacheSettings by their scenario key names ([hosts.page_cache] keys).
std::vector<std::pair<std::string, bool*>> cache_switches(CacheSettings& settings);

struct DiskSpec {
  std::string name;
  double read_bw = 0.0;
  double write_bw = 0.0;
  std::int64_t capacity = 0;  ///< bytes; 0: unlimited
};

struct HostConfig {
  std::string name;
  int cores = 1;
  std::int64_t memory = 0;
  /// Memory neither free nor reclaimable at the start (e.g. tmpfs contents): counted as
  /// application memory for the whole run.
  std::int64_t memory_in_use = 0;
  MemoryBandwidth memory_bandwidth;
  CacheSettings cache;
  std::vector<DiskSpec> disks;
};

/// A network link. Given its two hosts, it is also the route between them: a task on one may
/// use the other's files through it (as over an NFS mount). Without, it is crossed only by the
/// routes that name it (a platform file's links).
struct LinkSpec {
  std::string name;
  double bandwidth = 0.0;
  double latency = 0.0;
  std::string host_a;
  std::string host_b;
  LinkSharing sharing = LinkSharing::Shared;
};

/// The links between two hosts, in the order a transfer from host_a to host_b crosses them
/// (SimGrid's route; the same links serve the other direction).
struct RouteSpec {
  std::string host_a;
  std::string host_b;
  std::vector<std::string> links;
};

struct FileSpec {
  std::string name;
  std::int64_t size = 0;
  std::string host;  ///< where it is stored
  std::string disk;
  bool cached = false;  ///< in its host's page cache (clean) at time 0
};

/// One task: read files, compute, write files, then release its buffers.
struct TaskSpec {
  std::string name;
  /// Where a workflow task runs; empty: on a host of its workflow's (WorkflowSpec::hosts).
  std::string host;
  /// Cores it holds while it runs (workflow tasks: it waits until its host has them free).
  int cores = 1;
  /// Application memory it holds from its start to its end, the buffers of what it reads
  /// included: a task reading more holds what it reads (bytes; 0: only its buffers).
  std::int64_t memory = 0;
  std::vector<std::string> reads;
  double compute = 0.0;  ///< CPU seconds (on one core)
  std::vector<std::string> writes;
  std::int64_t chunk_size = 0;
  std::vector<std::string> after;  ///< workflow tasks that must end first (besides file producers)
  bool fsync = false;      ///< fsync each written file before the task ends
  bool direct_io = false;  ///< reads and writes bypass the page cache (O_DIRECT)
  std::vector<std::string> deletes;  ///< files deleted when the task ends
};

/// An application: tasks run one after the other on one host.
struct AppSpec {
  std::string name;
  std::string host;
  std::vector<TaskSpec> tasks;
};

/// A workflow: a DAG of tasks, each started when its inputs are ready (the tasks that write
/// them, and those named in `after`, have ended) and its host has the cores it needs free.
/// A task without a host of its own goes to the first of `hosts` with enough free cores the
/// moment it is ready; tasks waiting for cores are served in the order they became ready,
/// each as soon as some host has room for it.
struct WorkflowSpec {
  std::string name = "workflow";
  std::vector<std::string> hosts;  ///< at least one
  std::vector<TaskSpec> tasks;
  /// The workflow file it was read from (WfFormat JSON); empty if written in the scenario.
  std::string source;
};

struct Scenario {
  std::string source;  ///< the file it was read from ("<embedded>" for the default)
  std::string title;
  Profile profile = Profile::Linux;
  /// 0: one memory.csv row per change; else a host's row at each tick of this interval
  /// (seconds) at which its memory differs from its previous row.
  double memory_sample_interval = 1.0;
  /// `pcsim run` writes trace.json (Chrome Trace Event format) beside the other outputs.
  bool trace = false;
  std::vector<HostConfig> hosts;
  std::vector<LinkSpec> links;
  std::vector<RouteSpec> routes;
  std::vector<FileSpec> files;
  std::vector<AppSpec> apps;
  std::vector<WorkflowSpec> workflows;
  /// What the inputs hold that pcsim read but does not model, and what it took in place of a
  /// value beyond its range: "file:line: what", for the user to see (pcsim prints them).
  std::vector<std::string> warnings;
};

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
  /// Estimated events: three per chunk operation (each file's bytes over its task's chunk
  /// size, for every read and write), plus the flushers' periodic wake-ups over the estimated
  /// simulated time. About ten minutes of a run at the scale of 10^5 pipelines.
  double max_events = 3e9;
  /// Estimated simulated seconds: the longest of what the busiest disk, link or memory must
  /// move at its bandwidth and of what the busiest application must compute.
  double max_simulated_time = 1e8;
  /// Estimated memory.csv rows (held in memory until written): about 100 bytes each.
  double max_memory_rows = 2e7;

  /// Only what pcsim cannot represent: 5 * 10^8 tasks, 10^9 files, 10^9 s.
  static ScenarioLimits forced();
};

/// The links a transfer between two different hosts crosses: their route's, or the link
/// joining them; empty if none.
std::vector<const LinkSpec*> route_between(const Scenario& scenario, const std::string& a, const std::string& b);

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
