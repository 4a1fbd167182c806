#include "validate/switches.hpp"

#include <pagecache/error.hpp>

#include <fmt/format.h>

namespace pagecache::validate {

std::vector<std::pair<std::string, bool>> parse_switches(const std::vector<std::string>& switches) {
  std::vector<std::pair<std::string, bool>> out;
  for (const std::string& s : switches) {
    const auto eq = s.find('=');
    const std::string value = eq == std::string::npos ? "" : s.substr(eq + 1);
    if (eq == std::string::npos || eq == 0 || (value != "true" && value != "false")) {
      throw ConfigError(fmt::format("--switch '{}': expected --switch NAME=true|false, e.g. --switch background_writeback=false", s));
    }
    out.emplace_back(s.substr(0, eq), value == "true");
  }
  return out;
}

}  // namespace pagecache::validate
