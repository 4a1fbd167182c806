// load_workflow: a workflow instance on a platform, as `pcsim run WORKFLOW.json --platform P`
// gives them. The options become the values of a scenario document, each parsed with its
// option as its source, so that a problem with one names the option, not a line of a file
// nobody wrote.

#include <pagecache/error.hpp>
#include <pagecache/scenario_file.hpp>

#include "scenario/resolve.hpp"
#include "formats/common/text_file.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

namespace pagecache {

namespace {

// `value` as a TOML node whose source is `option`.
toml::table option_value(const std::string& option, toml::array value) {
  std::ostringstream text;
  text << toml::table{{"v", std::move(value)}};
  try {
    return toml::parse(text.str(), option);
  } catch (const toml::parse_error& e) {
    throw ConfigError(fmt::format("{}: {}", option, e.description()));
  }
}

std::string absolute(const std::string& path) { return std::filesystem::absolute(path).lexically_normal().string(); }

}  // namespace

// Moved, a node keeps its source (copied, it would not).
void scenario::insert_option(toml::table& into, const std::string& key, const std::string& option, toml::array value, bool as_array) {
  toml::table parsed = option_value(option, std::move(value));
  toml::array& values = *parsed.get_as<toml::array>("v");
  if (as_array) into.insert(key, std::move(values));
  else into.insert(key, std::move(*values.get(0)));
}

Scenario load_workflow(const std::string& workflow, const WorkflowOptions& options,
                       const std::vector<std::pair<std::string, std::string>>& overrides, const std::string& profile_override,
                       const ScenarioLimits& limits) {
  if (options.platform.empty()) {
    throw ConfigError(fmt::format("{}: a workflow file runs on a platform: add --platform PLATFORM.xml (SimGrid) or .toml", workflow));
  }
  // The files named on the command line, before a document is made around them.
  formats::check_text_file({}, workflow, "workflow file");
  formats::check_text_file("--platform", options.platform, "platform file");
  // Absolute: the document has no folder for them to be relative to.
  toml::table table{{"file", absolute(workflow)}};
  if (!options.files_host.empty()) {
    scenario::insert_option(table, "files_host", "--files-host " + options.files_host, toml::array{options.files_host}, false);
  }
  if (!options.hosts.empty()) {
    toml::array hosts;
    for (const std::string& h : options.hosts) hosts.push_back(h);
    scenario::insert_option(table, "hosts", fmt::format("--hosts {}", fmt::join(options.hosts, ",")), std::move(hosts), true);
  }
  toml::table root;
  scenario::insert_option(root, "platform", "--platform " + options.platform, toml::array{absolute(options.platform)}, false);
  root.insert("workflow", std::move(table));
  Scenario s = scenario::resolve_document(std::move(root), workflow, overrides, profile_override, limits);
  s.source = workflow;
  return s;
}

}  // namespace pagecache
