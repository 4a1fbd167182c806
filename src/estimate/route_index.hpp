#pragma once
// RouteIndex: the links between two hosts of a scenario, found in O(1) per pair: checking that
// every host a task may run on reaches its files asks once per pair of hosts, and a run on a
// cluster has 10^5 of them (route_between scans every route).

#include <pagecache/scenario.hpp>

#include <map>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace pagecache::estimate {

class RouteIndex {
 public:
  explicit RouteIndex(const Scenario& s) {
    std::unordered_map<std::string, const LinkSpec*> by_name;
    for (const LinkSpec& l : s.links) {
      by_name.emplace(l.name, &l);
      if (!l.host_a.empty()) routes_.emplace(key(l.host_a, l.host_b), std::vector<const LinkSpec*>{&l});
    }
    for (const RouteSpec& r : s.routes) {
      std::vector<const LinkSpec*> links;
      for (const std::string& name : r.links) {
        if (auto it = by_name.find(name); it != by_name.end()) links.push_back(it->second);
      }
      routes_.emplace(key(r.host_a, r.host_b), std::move(links));
    }
  }

  /// The links between two different hosts, in either direction; empty if none.
  const std::vector<const LinkSpec*>& between(const std::string& a, const std::string& b) const {
    static const std::vector<const LinkSpec*> none;
    const auto it = routes_.find(key(a, b));
    return it == routes_.end() ? none : it->second;
  }

 private:
  static std::pair<std::string, std::string> key(const std::string& a, const std::string& b) { return a < b ? std::pair{a, b} : std::pair{b, a}; }

  std::map<std::pair<std::string, std::string>, std::vector<const LinkSpec*>> routes_;
};

}  // namespace pagecache::estimate
