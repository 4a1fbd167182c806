// Reading a scenario file: TOML text -> overrides applied -> every key read and checked ->
// shorthands expanded -> references and sizes checked. resolve() reads the document's sections
// in a fixed order (loader_sections.hpp), so that the first problem is the one reported.

#include <pagecache/scenario.hpp>
#include <pagecache/scenario_file.hpp>

#include "scenario/deleted_files.hpp"
#include "scenario/limits.hpp"
#include "scenario/loader_sections.hpp"
#include "scenario/origins.hpp"
#include "scenario/resolve.hpp"
#include "formats/common/text_file.hpp"
#include "scenario/toml_reader.hpp"

#include <fmt/format.h>

#include <filesystem>

namespace pagecache {

namespace {

using scenario::Origins;
using scenario::Overrides;
using scenario::TomlReader;

// The scenario's own keys: its title, its profile (--profile, if given, wins over the file's),
// how often memory is sampled, whether the run is traced.
void read_settings(TomlReader& r, const std::string& profile_override, Scenario& s) {
  s.title = r.string("title", "");
  const std::string file_profile = r.string("profile", "linux");
  if (profile_override.empty()) {
    s.profile = scenario::parse_profile(file_profile, [&](const std::string& m) { r.fail("profile", m); });
  } else {
    s.profile = scenario::parse_profile(profile_override, [](const std::string& m) -> void { throw ConfigError("--profile: " + m); });
  }
  s.memory_sample_interval = r.optional_duration("memory_sample_interval").value_or(1.0);
  s.trace = r.optional_bool("trace").value_or(false);
}

// `platform_only`: a platform file shown alone (pcsim show PLATFORM): no workload, and what a run
// would need of the hosts (memory sizes and bandwidths) may be missing.
// `platform_overrides`: --set keys of the platform's hosts, links and routes, for a scenario
// that takes them from a TOML platform file (see parse_scenario).
Scenario resolve(const toml::table& root, const std::string& file, const std::string& profile_override, const ScenarioLimits& limits,
                 bool platform_only = false, const Overrides& platform_overrides = {}) {
  TomlReader r(root, "", file);
  Origins origins;
  origins.root = {&root, "", &file};
  Scenario s;
  s.source = file;
  read_settings(r, profile_override, s);

  scenario::PlatformFile platform;  // outlives the origins that point into it
  scenario::read_platform_file(r, file, platform_overrides, limits, s, origins, platform);
  scenario::read_host_defaults(r, file, platform.from_xml, s, origins);
  std::set<std::size_t> amendable = platform.from_xml;  // hosts of an XML platform, which [[hosts]] tables amend
  scenario::read_platform(r, s, file, limits, origins, amendable);
  if (s.hosts.empty()) r.fail_table("no host: add a [[hosts]] table, or a platform file");
  scenario::read_start(r, file, s);

  scenario::read_files(r, file, s, origins);
  scenario::read_file_sets(r, file, limits, s, origins);
  scenario::read_fio(r, file, limits, s, origins);
  // A workflow file before [pipelines], whose files' origins are all that table's (Origins::file).
  scenario::read_json_workflow(r, file, limits, s, origins);
  scenario::read_pipelines(r, file, limits, s, origins);
  scenario::read_apps(r, file, s, origins);
  scenario::read_workflow(r, file, s, origins);
  if (platform_only) {
    scenario::add_shown_routes(platform, s);
    r.finish();
    return s;
  }
  if (s.apps.empty() && s.workflows.empty()) {
    r.fail_table("no workload: add [pipelines], [[apps]] or [workflow] (or workflow = \"x.json\", a WfFormat file, or [fio] file = \"x.fio\")");
  }
  r.finish();
  if (platform.simgrid) scenario::keep_what_the_run_uses(*platform.simgrid, platform.from_xml, s, origins);

  // References: every file a task names exists on the task's host; files fit their disks.
  const std::map<std::string, const FileSpec*> files = scenario::check_files(s, origins);
  scenario::check_disk_space(s, origins);
  scenario::check_reach(s, file, files);
  scenario::check_workflow_cores(s, origins);
  scenario::check_reads_of_deleted_files(s, origins);
  scenario::check_limits(s, origins, limits);
  return s;
}

}  // namespace

Scenario parse_scenario(const std::string& toml_text, const std::string& source_name, const Overrides& overrides,
                        const std::string& profile_override, const ScenarioLimits& limits) {
  toml::table root;
  try {
    root = toml::parse(toml_text, source_name);
  } catch (const toml::parse_error& e) {
    throw ConfigError(fmt::format("{}:{}:{}: {}", source_name, e.source().begin.line, e.source().begin.column, e.description()),
                      InputPlace{.file = source_name, .line = static_cast<int>(e.source().begin.line), .key = {}});
  }
  return scenario::resolve_document(std::move(root), source_name, overrides, profile_override, limits);
}

Scenario scenario::resolve_document(toml::table root, const std::string& source_name, const Overrides& overrides,
                                    const std::string& profile_override, const ScenarioLimits& limits) {
  const Overrides of_platform = apply_overrides(root, overrides, source_name);
  return resolve(root, source_name, profile_override, limits, false, of_platform);
}

Scenario load_platform(const std::string& path, const std::string& profile_override) {
  // The file itself first: the document made around it is pcsim's, with no place to name.
  formats::check_text_file({}, path, "platform file");
  toml::table root;
  root.insert("platform", std::filesystem::path(path).filename().string());
  return resolve(root, path, profile_override, ScenarioLimits{}, true);
}

Scenario load_scenario(const std::string& path, const Overrides& overrides, const std::string& profile_override,
                       const ScenarioLimits& limits) {
  return parse_scenario(formats::read_text_file(path, "scenario file"), path, overrides, profile_override, limits);
}

}  // namespace pagecache
