#pragma once
// SgReader: the reader behind read_simgrid_platform, one pass over the elements in document
// order that builds the SgPlatform as it reads. Its parts: simgrid_reader.cpp (the platform,
// zones, hosts, links and routes), simgrid_cluster.cpp (a <cluster>, expanded into its hosts
// and links).

#include "scenario/simgrid_platform.hpp"
#include "scenario/simgrid_xml.hpp"

#include <pugixml.hpp>

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

namespace pagecache::scenario {

class SgReader {
 public:
  SgReader(const std::string& text, const std::string& file, const SgLimits& limits);

  SgPlatform read();

 private:
  enum class Policy { Shared, Fatpipe, SplitDuplex };
  struct ClusterLinks;  // simgrid_cluster.cpp

  static constexpr long long kMaxCores = 1'000'000;  // as the scenario loader's `cores`

  void platform(const pugi::xml_node& e);
  void config(const pugi::xml_node& e);
  void zone(const pugi::xml_node& e, int depth);
  std::size_t declare_zone(const pugi::xml_node& e);
  void host(const pugi::xml_node& e, std::size_t zone);
  SgDisk disk(const pugi::xml_node& e);
  void prop(const pugi::xml_node& e, SgProps& props, std::unordered_set<std::string>& ids);
  void warn_if_energy(const pugi::xml_node& e, std::string_view id);
  std::vector<double> speed_list(const pugi::xml_node& e);
  Policy sharing_policy(const pugi::xml_node& e, const char* name, Policy fallback, bool duplex_allowed);
  void link(const pugi::xml_node& e);
  void route(const pugi::xml_node& e, std::size_t zone);
  std::size_t route_end(const pugi::xml_node& e, const char* attribute, const std::string& id, std::size_t zone);
  std::string link_in_route(const pugi::xml_node& e);

  // A <cluster> (simgrid_cluster.cpp), in the steps of its reading.
  void cluster(const pugi::xml_node& e);
  void check_cluster_topology(const pugi::xml_node& e);
  SgHost cluster_node(const pugi::xml_node& e, const std::string& id, int line);
  ClusterLinks cluster_links(const pugi::xml_node& e, int line);
  SgCluster cluster_record(const pugi::xml_node& e, const std::string& id, int line, const ClusterLinks& links);
  void expand_cluster(const pugi::xml_node& e, const SgCluster& c, std::size_t zone, SgHost node, const ClusterLinks& links,
                      const std::string& prefix, const std::string& suffix);

  void check_new_host(const pugi::xml_node& e, const char* attribute, const std::string& id);
  void add_host(SgHost h, std::size_t zone);
  void add_link(SgLink l, const pugi::xml_node& e, const char* attribute);
  void add_split_duplex(SgLink l, const pugi::xml_node& e, const char* attribute);

  const std::string& text_;
  SgLimits limits_;
  SgPlatform platform_;
  SgXml xml_;
  std::unordered_map<std::string, std::size_t> host_at_;  // index into platform_.hosts
  std::vector<std::size_t> host_zone_;                    // per host, its zone's serial
  std::unordered_map<std::string, std::size_t> link_at_;  // index into platform_.links
  std::unordered_map<std::string, int> duplex_lines_;     // SPLITDUPLEX ids as written -> line
  std::vector<std::string> zone_ids_;                     // by serial (clusters are zones)
  std::unordered_map<std::string, int> zone_lines_;
  std::unordered_map<std::uint64_t, int> route_lines_;  // (src, dst) host indices -> line of its route
};

}  // namespace pagecache::scenario
