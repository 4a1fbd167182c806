// load_run_scenario: a scenario with the options `pcsim run` takes, as the command line and the
// Python module both load it.

#include <pagecache/error.hpp>
#include <pagecache/scenario_file.hpp>

#include <toml++/toml.h>

#include <filesystem>
#include <sstream>

namespace pagecache {

namespace {

// `text` as a TOML string value (an override's value is TOML).
std::string toml_string(const std::string& text) {
  std::ostringstream out;
  out << toml::value<std::string>(text);
  return out.str();
}

// The overrides of a scenario that is not a workflow instance: --platform is its `platform` key.
std::vector<std::pair<std::string, std::string>> scenario_overrides(const RunInputs& in) {
  if (!in.workflow.files_host.empty() || !in.workflow.hosts.empty()) {
    throw ConfigError("--files-host and --hosts place a workflow file's (JSON) files and tasks; a scenario gives them in its [workflow] table");
  }
  auto overrides = in.overrides;
  if (!in.workflow.platform.empty()) {
    const std::string platform = std::filesystem::absolute(in.workflow.platform).lexically_normal().string();
    overrides.insert(overrides.begin(), {"platform", toml_string(platform)});
  }
  return overrides;
}

bool is_workflow_file(const std::string& path) { return path.size() >= 5 && path.compare(path.size() - 5, 5, ".json") == 0; }

}  // namespace

Scenario load_run_scenario(const std::string& path, const RunInputs& in) {
  if (is_workflow_file(path)) return load_workflow(path, in.workflow, in.overrides, in.profile, in.limits);
  const auto overrides = scenario_overrides(in);
  if (path.empty()) return parse_scenario(default_scenario_text(), "<embedded default>", overrides, in.profile, in.limits);
  return load_scenario(path, overrides, in.profile, in.limits);
}

Scenario parse_run_scenario(const std::string& toml_text, const std::string& source_name, const RunInputs& in) {
  return parse_scenario(toml_text, source_name, scenario_overrides(in), in.profile, in.limits);
}

}  // namespace pagecache
