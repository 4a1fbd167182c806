#pragma once
// `pcsim validate --switch NAME=true|false`: the page-cache switches forced on every host.

#include <string>
#include <utility>
#include <vector>

namespace pagecache::validate {

/// Each "NAME=true" or "NAME=false" as (NAME, value); anything else is a ConfigError saying
/// what --switch expects. Whether NAME is a switch is checked against the hosts (validation.cpp).
std::vector<std::pair<std::string, bool>> parse_switches(const std::vector<std::string>& switches);

}  // namespace pagecache::validate
