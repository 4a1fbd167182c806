#pragma once
// Resolving a scenario document already read (loader.cpp), for those that make one rather
// than read it from a file: load_workflow (workflow_options.cpp) and a fio job file's run
// (run_inputs.cpp), whose values are pcsim's options.

#include <pagecache/scenario.hpp>
#include <pagecache/scenario_file.hpp>

#include "scenario/toml_reader.hpp"

#include <string>
#include <utility>
#include <vector>

namespace pagecache::scenario {

/// As parse_scenario, from the document `root`. A value whose source is one of pcsim's options
/// (a node parsed with the option as its source path, "--files-host x") is named by it in
/// messages (location(), toml_reader.hpp).
Scenario resolve_document(toml::table root, const std::string& source_name,
                          const std::vector<std::pair<std::string, std::string>>& overrides, const std::string& profile_override,
                          const ScenarioLimits& limits);

/// Inserts `value` (its one element, unless `as_array`) into `into` as `key`, parsed with
/// `option` ("--platform p.xml") as its source, so that a problem with it names the option.
void insert_option(toml::table& into, const std::string& key, const std::string& option, toml::array value, bool as_array);

}  // namespace pagecache::scenario
