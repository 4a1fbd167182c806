#pragma once
// SgReader: the reader behind read_simgrid_platform, one pass over the elements in document
// order that builds the SgPlatform as it reads. Its parts: formats/simgrid/xml/reader.cpp (the platform,
// zones, hosts and links), formats/simgrid/xml/zone_routes.cpp (routers, routes, routes between zones,
// bypasses, a Cluster zone's star), formats/simgrid/xml/cluster.cpp (a <cluster>, expanded into its hosts
// and links).

#include "formats/simgrid/routing/platform.hpp"
#include "formats/simgrid/xml/elements.hpp"

#include <pugixml.hpp>

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

namespace pagecache::formats::simgrid {

/// A <zone routing="Cluster">'s <host_link>s and <backbone>, made a star at the zone's end.
struct StarDraft {
  bool cluster = false;
  std::string backbone;
  std::vector<std::pair<std::string, std::pair<std::string, std::string>>> host_links;  // host -> (up, down)
  std::vector<pugi::xml_node> cabinets;  // made into hosts and links when the zone closes, as SimGrid does
};

class SgReader {
 public:
  SgReader(const std::string& text, const std::string& file, const SgLimits& limits);

  SgPlatform read();

 private:
  enum class Policy { Shared, Fatpipe, SplitDuplex };
  struct ClusterLinks;  // formats/simgrid/xml/cluster.cpp

  static constexpr long long kMaxCores = 1'000'000;  // as the scenario loader's `cores`

  void platform(const pugi::xml_node& e);
  void config(const pugi::xml_node& e);
  void zone(const pugi::xml_node& e, int depth, std::size_t parent);
  void zone_child(const pugi::xml_node& child, const pugi::xml_node& e, int depth, std::size_t zone, struct StarDraft& star);
  SgRouting routing_of(const pugi::xml_node& e);
  std::size_t declare_zone(const pugi::xml_node& e, std::size_t parent, SgRouting routing);
  void add_member(std::size_t zone, SgNetpoint n, const std::string& id, const pugi::xml_node& e, const char* attribute);
  void host(const pugi::xml_node& e, std::size_t zone);
  void trace(const pugi::xml_node& e);
  SgDisk disk(const pugi::xml_node& e);
  void prop(const pugi::xml_node& e, SgProps& props, std::unordered_set<std::string>& ids);
  void warn_if_energy(const pugi::xml_node& e, std::string_view id);
  std::vector<double> speed_list(const pugi::xml_node& e);
  Policy sharing_policy(const pugi::xml_node& e, const char* name, Policy fallback, bool duplex_allowed);
  void link(const pugi::xml_node& e);
  // Routes and what they go through (formats/simgrid/xml/zone_routes.cpp).
  void router(const pugi::xml_node& e, std::size_t zone);
  void route(const pugi::xml_node& e, std::size_t zone);
  SgNetpoint route_end(const pugi::xml_node& e, const char* attribute, const std::string& id, std::size_t zone);
  void zone_route(const pugi::xml_node& e, std::size_t zone, bool bypass);
  void check_gateway(const pugi::xml_node& e, const char* attribute, const std::string& id, std::size_t inside);
  void bypass_route(const pugi::xml_node& e, std::size_t zone);
  std::vector<std::string> links_of(const pugi::xml_node& e);
  bool symmetrical(const pugi::xml_node& e);
  void check_new_route(const pugi::xml_node& e, const SgRoute& r);
  std::string link_in_route(const pugi::xml_node& e);
  void host_link(const pugi::xml_node& e, std::size_t zone, struct StarDraft& star);
  void backbone(const pugi::xml_node& e, struct StarDraft& star);
  void finish_star(std::size_t zone, StarDraft& star);
  void cabinet(const pugi::xml_node& e, std::size_t zone, StarDraft& star);

  // A <cluster> (formats/simgrid/xml/cluster.cpp), in the steps of its reading.
  void cluster(const pugi::xml_node& e, std::size_t parent);
  SgTopology cluster_topology(const pugi::xml_node& e);
  SgHost cluster_node(const pugi::xml_node& e, const std::string& id, int line);
  ClusterLinks cluster_links(const pugi::xml_node& e, int line);
  SgCluster cluster_record(const pugi::xml_node& e, const std::string& id, int line, const ClusterLinks& links);
  void expand_topology(const pugi::xml_node& e, SgCluster& c, std::size_t zone, SgHost node, const ClusterLinks& links,
                       const std::string& prefix, const std::string& suffix);
  void expand_cluster(const pugi::xml_node& e, SgCluster& c, std::size_t zone, SgHost node, const ClusterLinks& links,
                      const std::string& prefix, const std::string& suffix);

  void check_new_host(const pugi::xml_node& e, const char* attribute, const std::string& id);
  void add_host(SgHost h, std::size_t zone, const pugi::xml_node& e, const char* attribute);
  void add_link(SgLink l, const pugi::xml_node& e, const char* attribute);
  void add_split_duplex(SgLink l, const pugi::xml_node& e, const char* attribute);

  const std::string& text_;
  SgLimits limits_;
  SgPlatform platform_;
  SgXml xml_;
  std::unordered_map<std::string, std::size_t> host_at_;  // index into platform_.hosts
  std::unordered_map<std::string, std::size_t> link_at_;  // index into platform_.links
  std::unordered_map<std::string, int> duplex_lines_;     // SPLITDUPLEX ids as written -> line
  std::unordered_map<std::string, SgNetpoint> netpoint_at_;  // hosts, routers and zones share SimGrid's names
  std::unordered_map<std::string, int> route_lines_;        // "src\ndst" -> line of its route (routes between zones too)
  std::unordered_map<std::string, int> bypass_lines_;
  // SimGrid's counters that run on across the clusters of a platform (formats/simgrid/routing/topology.hpp).
  std::size_t fat_tree_links_ = 0, dragonfly_links_ = 0;
  long fat_tree_positions_ = 0;       // "src\ndst" -> line of its bypass
};

}  // namespace pagecache::formats::simgrid
