// The resolved scenario's own functions (pagecache/scenario.hpp): the workload layer's, so
// that whatever runs or reports a Scenario needs nothing of the scenario files' layer.

#include <pagecache/scenario.hpp>

#include <algorithm>

namespace pagecache {

const char* to_string(Profile profile) { return profile == Profile::Paper ? "paper" : "linux"; }

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

std::vector<std::pair<std::string, bool*>> cache_switches(CacheSettings& s) {
  return {{"background_writeback", &s.background_writeback},
          {"dirty_throttling", &s.dirty_throttling},
          {"expire_oldest_first", &s.expire_oldest_first},
          {"two_touch_activation", &s.two_touch_activation},
          {"protect_files_being_written", &s.protect_files_being_written},
          {"dirtyable_memory", &s.dirtyable_memory},
          {"reclaim_inactive_only", &s.reclaim_inactive_only},
          {"reclaim_may_take_file_being_read", &s.reclaim_may_take_file_being_read},
          {"flush_splits_in_place", &s.flush_splits_in_place},
          {"balance_after_every_change", &s.balance_after_every_change},
          {"copies_hold_cores", &s.copies_hold_cores},
          {"large_folios", &s.large_folios}};
}

}  // namespace pagecache
