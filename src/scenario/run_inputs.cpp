// load_run_scenario: a scenario with the options `pcsim run` takes, as the command line and the
// Python module both load it.

#include <pagecache/error.hpp>
#include <pagecache/scenario_file.hpp>

#include "scenario/resolve.hpp"
#include "formats/common/text_file.hpp"
#include "text/path_problem.hpp"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <filesystem>
#include <sstream>
#include <string_view>
#include <utility>

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

bool ends_with(const std::string& path, const std::string& end) {
  return path.size() >= end.size() && path.compare(path.size() - end.size(), end.size(), end) == 0;
}

std::string absolute(const std::string& path) { return std::filesystem::absolute(path).lexically_normal().string(); }

// A fio job file on a platform: the scenario `platform = P` with `[fio] file = JOB`, so that
// --set reaches its keys (fio.host, fio.disk) as any scenario's.
Scenario load_fio(const std::string& path, const RunInputs& in) {
  if (in.workflow.platform.empty()) {
    throw ConfigError(fmt::format("{}: a fio job file runs on a platform: add --platform PLATFORM.toml (or a SimGrid .xml)", path));
  }
  if (!in.workflow.files_host.empty() || !in.workflow.hosts.empty()) {
    throw ConfigError("--files-host and --hosts place a workflow file's (JSON) files and tasks; a fio job file's run on one host (--set fio.host=NAME)");
  }
  // The files named on the command line, before a document is made around them.
  formats::check_text_file({}, path, "fio job file");
  formats::check_text_file("--platform", in.workflow.platform, "platform file");
  toml::table root{{"fio", toml::table{{"file", absolute(path)}}}};
  scenario::insert_option(root, "platform", "--platform " + in.workflow.platform, toml::array{absolute(in.workflow.platform)}, false);
  Scenario s = scenario::resolve_document(std::move(root), path, in.overrides, in.profile, in.limits);
  s.source = path;
  return s;
}

}  // namespace

Scenario load_run_scenario(const std::string& path, const RunInputs& in) {
  // A NUL cuts a path short for the system, and a message with one short for a C string reader.
  for (const auto& [argument, given] : {std::pair<std::string_view, const std::string&>{"", path}, {"--platform", in.workflow.platform}}) {
    if (const std::string nul = text::nul_problem(given); !nul.empty()) throw ConfigError(text::path_message(argument, given, nul));
  }
  if (ends_with(path, ".json")) return load_workflow(path, in.workflow, in.overrides, in.profile, in.limits);
  if (ends_with(path, ".fio")) return load_fio(path, in);
  const auto overrides = scenario_overrides(in);
  if (path.empty()) return parse_scenario(default_scenario_text(), "<embedded default>", overrides, in.profile, in.limits);
  return load_scenario(path, overrides, in.profile, in.limits);
}

Scenario parse_run_scenario(const std::string& toml_text, const std::string& source_name, const RunInputs& in) {
  return parse_scenario(toml_text, source_name, scenario_overrides(in), in.profile, in.limits);
}

}  // namespace pagecache
