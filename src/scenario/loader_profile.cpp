// A profile's name (the scenario's `profile`, or --profile) as the model profile it names.

#include "scenario/loader_sections.hpp"

#include <pagecache/scenario.hpp>

#include <fmt/format.h>

namespace pagecache::scenario {

Profile parse_profile(const std::string& name, const std::function<void(const std::string&)>& fail) {
  if (name == "paper") return Profile::Paper;
  if (name == "linux") return Profile::Linux;
  fail(fmt::format("unknown profile '{}' (use \"paper\" or \"linux\")", name));
  return Profile::Linux;
}

}  // namespace pagecache::scenario
