// The network of a scenario or platform file: [[links]] (a link between two hosts is also their
// route; one with a host group at an end is a link for each member) and [[routes]] (the links
// between two hosts, in order).

#include "scenario/loader_sections.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <tuple>

namespace pagecache::scenario {

namespace {

// What a link or route may name and what it may not join again. By name and by pair, not by
// scanning: a platform shown from a cluster run has 10^4 of each.
struct KnownNetwork {
  std::set<std::string> host_names, link_names;
  std::set<std::pair<std::string, std::string>> joined;  // hosts with a link or route, each pair in order

  explicit KnownNetwork(const Scenario& s) {
    for (const HostConfig& h : s.hosts) host_names.insert(h.name);
    for (const LinkSpec& l : s.links) {
      link_names.insert(l.name);
      if (!l.host_a.empty()) joined.insert(std::minmax(l.host_a, l.host_b));
    }
    for (const RouteSpec& rs : s.routes) joined.insert(std::minmax(rs.host_a, rs.host_b));
  }

  // hosts = ["a", "b"] of a link or route: two different known hosts not joined yet.
  std::pair<std::string, std::string> read_ends(TomlReader& t, const char* what) {
    const std::vector<std::string> ends = t.names("hosts");
    if (ends.size() != 2 || ends[0] == ends[1]) t.fail("hosts", fmt::format("a {} joins two different hosts: hosts = [\"a\", \"b\"]", what));
    for (const std::string& end : ends) {
      if (host_names.count(end) == 0) t.fail("hosts", fmt::format("no host named '{}'", end));
    }
    if (!joined.insert(std::minmax(ends[0], ends[1])).second) t.fail("hosts", "these hosts already have a link or a route");
    return std::pair{ends[0], ends[1]};
  }
};

// A link between host group `group` and host `other`: a link of its own for each member, named
// after the link, each with the link's table as its origin.
void add_group_links(TomlReader& l, const LinkSpec& link, const std::string& group, const std::string& other, Scenario& s, Origins& origins,
                     KnownNetwork& known) {
  if (origins.host_groups.count(other) != 0) l.fail("hosts", "a link joins a host group to one host, not two groups");
  if (known.host_names.count(other) == 0) l.fail("hosts", fmt::format("no host named '{}'", other));
  l.finish();
  const auto [first, count] = origins.host_groups.at(group);
  for (std::size_t k = 0; k < count; ++k) {
    LinkSpec& member = s.links.emplace_back(link);
    member.name = fmt::format("{}-{}", link.name, k + 1);
    member.host_a = s.hosts[first + k].name;
    member.host_b = other;
    if (!known.link_names.insert(member.name).second) l.fail("name", fmt::format("two links named '{}'", member.name));
    if (!known.joined.insert(std::minmax(member.host_a, member.host_b)).second) {
      l.fail("hosts", fmt::format("hosts '{}' and '{}' already have a link or a route", member.host_a, member.host_b));
    }
    const Origin origin = origins.links.back();
    origins.links.push_back(origin);
  }
  origins.links.pop_back();  // one per link made
}

void read_links(TomlReader& r, Scenario& s, const std::string& file, Origins& origins, KnownNetwork& known) {
  const auto links = r.tables("links");
  for (std::size_t i = 0; i < links.size(); ++i) {
    TomlReader l(*links[i], r.child_path("links", i), file);
    origins.links.push_back({links[i], l.path(), &file});
    LinkSpec link;
    link.name = l.name("name", fmt::format("link{}", s.links.size() + 1));
    link.bandwidth = l.required_bandwidth("bandwidth");
    link.latency = l.optional_duration("latency").value_or(0.0);
    if (auto sharing = l.optional_string("sharing")) {
      if (*sharing == "fatpipe") link.sharing = pagecache::LinkSharing::Fatpipe;
      else if (*sharing != "shared") l.fail("sharing", fmt::format("unknown sharing '{}' (use \"shared\" or \"fatpipe\")", *sharing));
    }
    if (!known.link_names.insert(link.name).second) l.fail("name", fmt::format("two links named '{}'", link.name));
    // A host group at one end: a link of its own for each member, named after the link.
    const std::vector<std::string> ends = l.has("hosts") ? l.names("hosts") : std::vector<std::string>{};
    const auto group = ends.size() == 2 ? std::find_if(ends.begin(), ends.end(), [&](const std::string& e) { return origins.host_groups.count(e) != 0; })
                                        : ends.end();
    if (group == ends.end()) {
      // Without hosts, a link is crossed only by the routes that name it.
      if (l.has("hosts")) std::tie(link.host_a, link.host_b) = known.read_ends(l, "link");
      l.finish();
      s.links.push_back(std::move(link));
      continue;
    }
    add_group_links(l, link, *group, *group == ends[0] ? ends[1] : ends[0], s, origins, known);
  }
}

void read_routes(TomlReader& r, Scenario& s, const std::string& file, Origins& origins, KnownNetwork& known) {
  const auto routes = r.tables("routes");
  for (std::size_t i = 0; i < routes.size(); ++i) {
    TomlReader rt(*routes[i], r.child_path("routes", i), file);
    origins.routes.push_back({routes[i], rt.path(), &file});
    RouteSpec route;
    std::tie(route.host_a, route.host_b) = known.read_ends(rt, "route");
    route.links = rt.names("links");
    if (route.links.empty()) rt.fail("links", "a route crosses at least one link");
    for (const std::string& name : route.links) {
      if (known.link_names.count(name) == 0) rt.fail("links", fmt::format("no link named '{}'", name));
    }
    rt.finish();
    s.routes.push_back(std::move(route));
  }
}

}  // namespace

void read_network(TomlReader& r, Scenario& s, const std::string& file, Origins& origins) {
  KnownNetwork known(s);
  read_links(r, s, file, origins, known);
  read_routes(r, s, file, origins, known);
}

}  // namespace pagecache::scenario
