#pragma once
// SgRouteFinder: the route between two hosts of an SgPlatform as SimGrid's NetZoneImpl finds
// it. The common ancestor zone of the two hosts is found; a bypass route of that zone is taken
// if one applies; else, in the same zone, the zone's local route; else the ancestor's route
// between the two sub-zones (or netpoints) holding them, completed at each end by the route to
// or from its gateway, found the same way. A zone's local route follows its routing kind:
// Full the declared route, Floyd and Dijkstra the fewest links over declared routes (SimGrid's
// tie rules: formats/simgrid/routing/shortest.cpp), Cluster the star, None nothing.
//
// Routes are found on request: nothing is listed for all pairs. Floyd's tables are built for a
// zone the first time one of its routes is asked for.

#include "formats/simgrid/routing/platform.hpp"
#include "formats/simgrid/routing/topology.hpp"

#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

namespace pagecache::formats::simgrid {

/// A zone's route between two of its netpoints: its links, and for a route between zones the
/// gateways it leaves and enters by.
struct SgLocalRoute {
  std::vector<std::string> links;
  std::optional<SgNetpoint> gw_src;
  std::optional<SgNetpoint> gw_dst;
};

/// A declared route seen from one direction: SgPlatform::routes[route], or ::zone_routes[route]
/// when not `written`.
struct SgEdge {
  std::size_t route = 0;
  bool written = false;
  bool reversed = false;
  const SgRoute& of(const SgPlatform& p) const { return written ? p.routes[route] : p.zone_routes[route]; }
};

class SgRouteFinder {
 public:
  /// Indexes `p`. The finder keeps indices only: each query is given `p` or an equal copy.
  explicit SgRouteFinder(const SgPlatform& p);
  ~SgRouteFinder();

  /// SimGrid's route from host a to host b (indices into hosts) into `links`; false if there is
  /// none, or it has no link (a zone with routing None). Safe to call from several threads.
  bool host_route(const SgPlatform& p, std::size_t a, std::size_t b, std::vector<std::string>& links) const;

  // What formats/simgrid/routing/shortest.cpp needs.
  std::size_t zone_count() const { return edges_.size(); }
  std::size_t members(std::size_t zone) const { return members_[zone]; }
  /// The zone's declared route from vertex `from` to vertex `to` (SimGrid's edge), if any.
  const SgEdge* edge(std::size_t zone, std::size_t from, std::size_t to) const;
  /// The declared edges of a zone, in order of declaration (a symmetrical route's two).
  struct ZoneEdge {
    std::size_t from, to;
    SgEdge edge;
    int line;
    std::size_t links;  // its weight: SimGrid counts a route's links
  };
  const std::vector<ZoneEdge>& edges_of(std::size_t zone) const { return edges_[zone]; }
  /// A netpoint's vertex number in its zone (SimGrid's NetPoint::id()).
  std::size_t vertex(SgNetpoint n) const;
  /// The edge's links from `from` to `to`, a reversed route swapping SPLITDUPLEX halves; gateways too.
  SgLocalRoute local_of(const SgPlatform& p, const SgEdge& e) const;
  /// Whether SimGrid routes the zone recursively (it has sub-zones): gateways are then joined.
  bool recursive(std::size_t zone) const { return recursive_[zone]; }
  /// SimGrid's global route between two netpoints, appended to `links`.
  bool global(const SgPlatform& p, SgNetpoint src, SgNetpoint dst, std::vector<std::string>& links, int depth) const;

 private:
  struct Shortest;  // formats/simgrid/routing/shortest.cpp: Floyd's tables and Dijkstra's per zone

  std::size_t zone_of(const SgPlatform& p, SgNetpoint n) const;
  std::vector<std::size_t> zones_from_root(const SgPlatform& p, SgNetpoint n) const;
  bool local(const SgPlatform& p, std::size_t zone, SgNetpoint src, SgNetpoint dst, SgLocalRoute& out, int depth) const;
  bool star(const SgPlatform& p, std::size_t zone, SgNetpoint src, SgNetpoint dst, SgLocalRoute& out) const;
  bool bypass(const SgPlatform& p, std::size_t common, SgNetpoint src, SgNetpoint dst, std::vector<std::string>& links, int depth) const;
  std::optional<SgNetpoint> netpoint(const std::string& id) const;

  std::vector<std::size_t> members_;  // per zone, its vertices
  std::unordered_map<std::string, SgNetpoint> netpoint_at_;
  std::vector<std::size_t> host_vertex_, router_vertex_, zone_vertex_;
  std::vector<std::vector<ZoneEdge>> edges_;                          // per zone
  std::vector<std::unordered_map<std::uint64_t, SgEdge>> edge_at_;    // per zone, by (from, to) vertices
  std::vector<std::unordered_map<std::uint64_t, std::size_t>> bypass_at_;  // per zone, by (src, dst) netpoints
  std::vector<bool> recursive_;
  std::vector<std::unordered_map<std::string, std::pair<std::size_t, std::size_t>>> star_ways_;  // (star, way) per id  // per zone with routing Cluster
  std::unique_ptr<Shortest> shortest_;
  std::vector<std::unique_ptr<SgFatTree>> trees_;    // per cluster, a FAT_TREE's
  std::vector<std::unique_ptr<SgDragonfly>> flies_;  // per cluster, a DRAGONFLY's
};

}  // namespace pagecache::formats::simgrid
