#pragma once
// The SimGrid platform reader's contract, as fuzz/platform_fuzzer.cpp checks it on every input
// and tests/scenario/simgrid_platform_test.cpp replays it on the inputs the fuzzer found: any
// bytes either read as a platform or are refused with a ConfigError whose message starts with
// "FILE:LINE:"; any other exception, a crash, a hang, unbounded memory or a sanitizer report is
// a bug. A platform that reads is consistent: host ids unique, quantities positive and finite,
// every route's links declared, and find_route agreeing with the routes it lists.

#include <pagecache/error.hpp>

#include "formats/simgrid/routing/platform.hpp"

#include <cctype>
#include <cmath>
#include <string>
#include <unordered_set>

namespace pagecache::fuzz {

/// The bounds inputs are read with: the defaults let a cluster of 10^5 nodes through, whose
/// 5 * 10^9 routes the checks below could not visit, and even SimGrid's example of 100 nodes
/// (cluster_backbone.xml, 5050 routes) takes 15 ms under the sanitizers, 30 times a typical
/// input. The code that enforces them is the same; a cluster of 30 has all its forms.
inline formats::simgrid::SgLimits fuzz_platform_limits() { return {.max_cluster_hosts = 30, .max_hosts = 100}; }

/// "" if `text` keeps the contract, else what broke. Exceptions other than ConfigError are not
/// caught: in the fuzzer they end the process where they were thrown, in a test Catch2 reports them.
inline std::string check_platform_text(const std::string& text, const std::string& file) {
  using namespace formats::simgrid;
  SgPlatform p;
  try {
    p = read_simgrid_platform(text, file, fuzz_platform_limits());
  } catch (const ConfigError& e) {
    const std::string message = e.what();
    std::size_t i = file.size() + 1;
    const bool located = message.compare(0, i, file + ":") == 0 && i < message.size() && std::isdigit(static_cast<unsigned char>(message[i]));
    while (i < message.size() && std::isdigit(static_cast<unsigned char>(message[i]))) ++i;
    if (!located || i >= message.size() || message[i] != ':') return "a ConfigError without FILE:LINE: " + message;
    return {};
  }
  const auto positive = [](double x) { return std::isfinite(x) && x > 0; };
  std::unordered_set<std::string> ids;
  for (const SgHost& h : p.hosts) {
    if (!ids.insert(h.id).second) return "host '" + h.id + "' twice";
    if (p.find_host(h.id) != &h) return "find_host('" + h.id + "') is not the host";
    if (!positive(h.speed) || h.cores < 1 || h.line < 1) return "host '" + h.id + "' has a bad speed, core count or line";
    for (const SgDisk& d : h.disks) {
      if (!positive(d.read_bw) || !positive(d.write_bw)) return "disk '" + d.id + "' has a bad bandwidth";
    }
  }
  ids.clear();
  for (const SgLink& l : p.links) {
    if (!ids.insert(l.id).second) return "link '" + l.id + "' twice";
    if (p.find_link(l.id) != &l) return "find_link('" + l.id + "') is not the link";
    if (!positive(l.bandwidth) || !std::isfinite(l.latency) || l.latency < 0) return "link '" + l.id + "' has a bad bandwidth or latency";
  }
  // All the routes as written, and the first of the clusters' (a cluster of 100 has 5050).
  constexpr std::size_t kRoutesChecked = 500;
  std::size_t visited = 0;
  std::string broken;
  const auto check = [&](const SgRoute& r) {
    if (!broken.empty() || ++visited > p.routes.size() + kRoutesChecked) return;
    if (p.find_host(r.src) == nullptr || p.find_host(r.dst) == nullptr) broken = "a route between unknown hosts";
    if (r.links.empty()) broken = "a route with no link from '" + r.src + "' to '" + r.dst + "'";
    for (const std::string& l : r.links) {
      if (p.find_link(l) == nullptr) broken = "route from '" + r.src + "' to '" + r.dst + "': unknown link '" + l + "'";
    }
    const SgRoute* found = p.find_route(r.src, r.dst);
    if (found == nullptr || found->src != r.src || found->dst != r.dst || found->links != r.links) {
      broken = "find_route('" + r.src + "', '" + r.dst + "') disagrees with the route listed";
      return;
    }
    if (!r.symmetrical || r.src == r.dst) return;
    const SgRoute* back = p.find_route(r.dst, r.src);
    if (back == nullptr || back->src != r.dst || back->dst != r.src || back->links.size() != r.links.size()) {
      broken = "find_route('" + r.dst + "', '" + r.src + "') is not the way back of a symmetrical route";
      return;
    }
    for (std::size_t i = 0; i < r.links.size(); ++i) {
      const SgLink* there = p.find_link(r.links[i]);
      const SgLink* again = p.find_link(back->links[r.links.size() - 1 - i]);
      const bool same = there == again && there->half == DuplexHalf::None;
      const bool swapped = there != nullptr && again != nullptr && there->half != DuplexHalf::None && again->half != DuplexHalf::None &&
                           there->half != again->half && there->duplex_id == again->duplex_id;
      if (!same && !swapped) broken = "the way back from '" + r.dst + "' to '" + r.src + "' is not the way there reversed";
    }
  };
  p.for_each_route(check);
  return broken;
}

}  // namespace pagecache::fuzz
