#pragma once
// The scenario loader's sections, each a reader of its part of a scenario document (loader.cpp's
// resolve calls them in the order below, which is the order of its messages): the platform
// file, the hosts with their disks and page caches, the network, the start state, the files,
// the workload (a workflow file, pipelines, applications, a workflow), then the checks of the
// whole. Each takes its keys from the document's root reader `r`, adds what it reads to the
// Scenario and where each element was written to Origins, so that a later check can still
// name the file, line and key of what it refuses.

#include <pagecache/scenario.hpp>
#include <pagecache/scenario_file.hpp>

#include "scenario/origins.hpp"
#include "formats/simgrid/routing/platform.hpp"
#include "scenario/toml_reader.hpp"

#include <cstddef>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

namespace pagecache::scenario {

/// --set KEY=VALUE pairs, in the order given.
using Overrides = std::vector<std::pair<std::string, std::string>>;

// The options' say (loader_profile.cpp, loader_overrides.cpp).

/// "paper" or "linux"; `fail(message)` reports any other name and must throw.
Profile parse_profile(const std::string& name, const std::function<void(const std::string&)>& fail);
/// Sets the dotted `key` of `root` to `value` (--set KEY=VALUE); `source` is named in messages.
void apply_override(toml::table& root, const std::string& key, const std::string& value, const std::string& source);
/// Applies `overrides` to `root` in order, but for those of the hosts, links and routes of the
/// platform file `root` names, which it returns (applied to that file's table when it is read).
Overrides apply_overrides(toml::table& root, const Overrides& overrides, const std::string& source);

// The platform (loader_platform.cpp).

/// A path written in `file`, relative to its folder.
inline std::string relative_path(const std::string& file, const std::string& path) {
  const std::filesystem::path relative_to = std::filesystem::path(file).parent_path();
  return std::filesystem::path(path).is_absolute() ? path : (relative_to / path).lexically_normal().string();
}

/// The platform file a scenario names (`platform = ...`), as read. Origins point into it: it
/// stays where it was made until they are done with.
struct PlatformFile {
  std::string file;  ///< empty: none
  toml::table root;  ///< a TOML platform's document
  std::optional<formats::simgrid::SgPlatform> simgrid;  ///< an XML one, kept until the run's routes are known
  std::set<std::size_t> from_xml;     ///< the hosts the XML file gave

  PlatformFile() = default;
  PlatformFile(const PlatformFile&) = delete;
  PlatformFile& operator=(const PlatformFile&) = delete;
};

/// platform = "file.toml" or "file.xml" (SimGrid), or one per profile: its hosts, links and
/// routes (those of a TOML file with `platform_overrides` applied) added to `s`.
void read_platform_file(TomlReader& r, const std::string& file, const Overrides& platform_overrides, const ScenarioLimits& limits, Scenario& s, Origins& origins,
                        PlatformFile& platform);
/// The platform part of a scenario or of a platform file: [[hosts]], [[links]] and [[routes]].
/// `amendable`: the hosts a [[hosts]] table of their name amends (once each, then erased).
void read_platform(TomlReader& r, Scenario& s, const std::string& file, const ScenarioLimits& limits, Origins& origins, std::set<std::size_t>& amendable);
/// `pcsim show` of a platform alone: the routes of its SimGrid file, up to a bound.
void add_shown_routes(const PlatformFile& platform, Scenario& s);
/// A run on a SimGrid platform keeps the hosts, routes and links it uses; see the definition.
void keep_what_the_run_uses(const formats::simgrid::SgPlatform& platform, const std::set<std::size_t>& from_xml, Scenario& s, Origins& origins);

// The hosts (loader_hosts.cpp) and the network (loader_network.cpp).

/// The [[hosts]] tables of `r`, new hosts and host groups or amendments of `amendable` ones.
void read_hosts(TomlReader& r, Scenario& s, const std::string& file, const ScenarioLimits& limits, Origins& origins, std::set<std::size_t>& amendable);
/// A speed at `key` of `r`, in flop/s: a number, or a string in SimGrid's units ("1.2Gf");
/// it must be > 0.
std::optional<double> read_speed(TomlReader& r, const std::string& key);
/// [host_defaults]: what the hosts of a SimGrid platform (`from_xml`) lack.
void read_host_defaults(TomlReader& r, const std::string& file, const std::set<std::size_t>& from_xml, Scenario& s, Origins& origins);
/// [start.memory_in_use]: the memory in use of named hosts when the run starts.
void read_start(TomlReader& r, const std::string& file, Scenario& s);
/// The [[links]] and [[routes]] tables of `r`, between the hosts `s` has.
void read_network(TomlReader& r, Scenario& s, const std::string& file, Origins& origins);

// The files (loader_files.cpp).

/// The [[files]] tables.
void read_files(TomlReader& r, const std::string& file, Scenario& s, Origins& origins);
/// The [[file_sets]] tables (after the hosts).
void read_file_sets(TomlReader& r, const std::string& file, const ScenarioLimits& limits, Scenario& s, Origins& origins);
/// Each file of `s` named once and on a disk of its host that it fits; returns them by name.
std::map<std::string, const FileSpec*> check_files(const Scenario& s, const Origins& origins);
/// The files on each disk fit its capacity at the start and at the end of the run.
void check_disk_space(const Scenario& s, const Origins& origins);

// The workload (loader_apps.cpp, loader_workflow.cpp).

/// memory_max / memory_high: the limits of a memory group (`whose`: whose, for the message).
/// Absent: `inherited` (a workflow's for its tasks), unless memory_max is given here.
MemoryLimits read_memory_limits(TomlReader& r, const char* whose, MemoryLimits inherited = {});
/// What tasks' accesses may name: the file sets, and the files, indexed by name when first
/// asked (most scenarios have no access of one file; some have 10^6 files).
class AccessTargets {
 public:
  explicit AccessTargets(const Scenario& s) : sets_(s.file_sets), files_(s.files) {}
  const std::vector<FileSetSpec>& sets() const noexcept { return sets_; }
  /// The file named `name`, or nullptr.
  const FileSpec* file(const std::string& name);

 private:
  const std::vector<FileSetSpec>& sets_;
  const std::vector<FileSpec>& files_;
  std::unordered_map<std::string_view, const FileSpec*> index_;
};

/// A [[apps.tasks]] or [[workflow.tasks]] table (`in_workflow`: the latter's keys too); its
/// accesses name the file sets and files of `targets`.
TaskSpec read_task(const toml::table& table, std::string path, std::size_t index, std::int64_t default_chunk, const std::string& file,
                   AccessTargets& targets, bool in_workflow, MemoryLimits workflow_limits = {});
/// A task's [[access]] tables (loader_access.cpp), each over a set or a file of `targets`; an
/// access of one file requests `chunk_size` bytes at a time unless it says otherwise.
std::vector<AccessSpec> read_accesses(TomlReader& task, AccessTargets& targets, std::int64_t chunk_size);
/// [pipelines]: applications and files made by the pattern it describes.
void read_pipelines(TomlReader& r, const std::string& file, const ScenarioLimits& limits, Scenario& s, Origins& origins);
/// The [[apps]] tables.
void read_apps(TomlReader& r, const std::string& file, Scenario& s, Origins& origins);
/// [fio]: a fio job file's jobs as applications and their files (loader_fio.cpp); alone.
void read_fio(TomlReader& r, const std::string& file, const ScenarioLimits& limits, Scenario& s, Origins& origins);
/// workflow = "x.json", or [workflow] with file = "x.json": a WfFormat instance and its files.
void read_json_workflow(TomlReader& r, const std::string& file, const ScenarioLimits& limits, Scenario& s, Origins& origins);
/// A [workflow] table with its [[workflow.tasks]], when no workflow file was read.
void read_workflow(TomlReader& r, const std::string& file, Scenario& s, Origins& origins);

// The checks of the whole (loader_reach.cpp, loader_workflow.cpp).

/// Every host a task may run on reaches the files it names, over a route pcsim models.
/// `file`: the scenario's, named for the tasks read from it.
void check_reach(const Scenario& s, const std::string& file, const std::map<std::string, const FileSpec*>& files);
/// No workflow task needs more cores than the hosts it may run on have.
void check_workflow_cores(const Scenario& s, const Origins& origins);

}  // namespace pagecache::scenario
