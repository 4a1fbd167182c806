// The resolved scenario's own functions (pagecache/scenario.hpp): the workload layer's, so
// that whatever runs or reports a Scenario needs nothing of the scenario files' layer.

#include <pagecache/scenario.hpp>

#include <algorithm>

namespace pagecache {

const char* to_string(Profile profile) { return profile == Profile::Paper ? "paper" : "linux"; }

const char* to_string(AccessPattern pattern) {
  switch (pattern) {
    case AccessPattern::Random: return "random";
    case AccessPattern::Strided: return "strided";
    case AccessPattern::Ranges: return "ranges";
    case AccessPattern::Sequential: break;
  }
  return "sequential";
}

const char* to_string(AccessMode mode) { return mode == AccessMode::Write ? "write" : mode == AccessMode::Append ? "append" : "read"; }

const char* to_string(AccessAdvice advice) {
  return advice == AccessAdvice::Sequential ? "sequential" : advice == AccessAdvice::Random ? "random" : "normal";
}

CacheSettings settings_for(Profile profile) {
  return profile == Profile::Paper ? CacheSettings::paper() : CacheSettings::kernel();
}

std::vector<const LinkSpec*> route_between(const Scenario& scenario, const std::string& a, const std::string& b) {
  std::vector<const LinkSpec*> links;
  for (const RouteSpec& r : scenario.routes) {
    if ((r.host_a == a && r.host_b == b) || (r.host_a == b && r.host_b == a)) {
      for (const std::string& name : r.links) {
        const auto l = std::find_if(scenario.links.begin(), scenario.links.end(), [&](const LinkSpec& x) { return x.name == name; });
        if (l != scenario.links.end()) links.push_back(&*l);
      }
      return links;
    }
  }
  for (const LinkSpec& l : scenario.links) {
    if ((l.host_a == a && l.host_b == b) || (l.host_a == b && l.host_b == a)) return {&l};
  }
  return links;
}


}  // namespace pagecache
