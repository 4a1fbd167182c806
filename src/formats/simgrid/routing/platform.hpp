#pragma once
// A SimGrid platform file (XML, DTD versions 4 and 4.1) read into plain structs, for pcsim to
// build its own platform from: hosts (speed, cores, properties, disks), network links, and the
// routes between hosts as ordered lists of link ids. Everything that can change a simulation
// result is read and checked; what pcsim cannot represent (Vivaldi and Wifi zones, profiles
// that change hosts and links over time, WIFI links) is refused with ConfigError naming the
// file, line, element and attribute; what cannot change a result is ignored with a warning.
//
// Zones nest as SimGrid's netzones: each has a routing kind (SgRouting) and netpoints (hosts,
// routers, its sub-zones), and a route between two hosts is SimGrid's global route
// (formats/simgrid/routing/routing.hpp): through their common ancestor zone and the gateways of its
// <zoneRoute>s, a <bypassRoute> taking precedence.
//
// Units are SimGrid's (formats/simgrid/xml/units.hpp), stored in SI: bandwidths in bytes/s, latencies in
// seconds, speeds in flop/s.
//
// A SPLITDUPLEX link X becomes the two links X_UP and X_DOWN, and a route names the half it
// uses (link_ctn direction="UP"). A route declared symmetrical (SimGrid's default) also serves
// dst -> src over the same links in reverse order, each half of a SPLITDUPLEX link swapped for
// the other, which is SimGrid's rule.
//
// A <cluster> (FLAT topology) expands as SimGrid expands it: hosts prefix + N + suffix for
// each N of its radical, in that order; for each node a private link <cluster>_link_<N>
// (halves _UP and _DOWN when SPLITDUPLEX, the cluster default), a <cluster>_link_<N>_limiter
// if limiter_link is given, a FATPIPE <cluster>_link_<N>_loopback if loopback_bw is given;
// a <cluster>_backbone if bb_bw is given; then its router, the zone's gateway. Its n(n - 1)
// routes are not stored: SgCluster computes one on request (SimGrid's star routing),
// find_route returns it and for_each_route lists them all. A TORUS, FAT_TREE or DRAGONFLY
// cluster is expanded and routed as formats/simgrid/routing/topology.hpp says.

#include <pagecache/error.hpp>

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace pagecache::formats::simgrid {

using SgProps = std::vector<std::pair<std::string, std::string>>;

enum class LinkSharing { Shared, Fatpipe };

/// Which half of a SPLITDUPLEX link a link is, if any.
enum class DuplexHalf { None, Up, Down };

struct SgDisk {
  std::string id;
  double read_bw = 0;   // bytes/s
  double write_bw = 0;  // bytes/s
  SgProps props;        // in document order (size, mount, ... as written: see parse_sg_size)
  int line = 0;
};

/// How a zone finds routes between its netpoints (SimGrid's routing="..."): Full takes the
/// declared routes, Floyd / Dijkstra / DijkstraCache the fewest links over them, Cluster a star
/// (each netpoint's way up, then the other's way down), None none.
enum class SgRouting { Full, Floyd, Dijkstra, DijkstraCache, Cluster, None };

inline constexpr std::size_t kNoZone = static_cast<std::size_t>(-1);

/// A place routes start and end at: a host, a router, or a zone within its parent.
struct SgNetpoint {
  enum class Kind : unsigned char { Host, Router, Zone };
  Kind kind = Kind::Host;
  std::size_t index = 0;  // into SgPlatform::hosts, ::routers or ::zones
  bool operator==(const SgNetpoint&) const = default;
};

struct SgZone {
  std::string id;
  SgRouting routing = SgRouting::Full;
  std::size_t parent = kNoZone;          // the root zone has none
  std::vector<SgNetpoint> members;       // SimGrid's vertices: hosts, routers, sub-zones in order of declaration
  std::size_t cluster = kNoZone;         // of a <cluster>: its index in SgPlatform::clusters
  std::size_t star = kNoZone;            // of a <zone routing="Cluster">: its index in SgPlatform::stars
  int line = 0;
};

/// A netpoint without a host: a route may go through it, nothing runs on it.
struct SgRouter {
  std::string id;
  std::size_t zone = 0;
  int line = 0;
};

struct SgHost {
  std::string id;
  double speed = 0;  // flop/s, of the pstate the host starts in (attribute pstate, default 0)
  int cores = 1;
  SgProps props;     // in document order; a cluster's props are given to each of its hosts
  std::vector<SgDisk> disks;
  std::string cluster;  // the id of the <cluster> that made this host, else empty
  int line = 0;
  std::size_t zone = 0;  // the zone that holds it (a cluster's own zone for a cluster's node)
};

struct SgLink {
  std::string id;
  double bandwidth = 0;  // bytes/s
  double latency = 0;    // s
  LinkSharing sharing = LinkSharing::Shared;
  DuplexHalf half = DuplexHalf::None;
  std::string duplex_id;  // for a half: the SPLITDUPLEX link's id as written ("X" of "X_UP")
  SgProps props;
  int line = 0;
};

struct SgRoute {
  std::string src;
  std::string dst;
  std::vector<std::string> links;  // ids into SgPlatform::links, in order from src to dst
  bool symmetrical = true;         // also serves dst -> src (see the top of this header)
  int line = 0;
  // Of a declared route between zones (<zoneRoute>, <bypassZoneRoute>): the netpoints it leaves and enters by.
  std::string gw_src;
  std::string gw_dst;
  std::size_t zone = 0;  // the zone it is declared in
};

/// The star of a Cluster zone: a <cluster>'s hosts with the links it makes, or a
/// <zone routing="Cluster">'s <host_link>s and <backbone>. Netpoints without ways (a
/// router) join the star with no link.
struct SgStar {
  struct Ways {
    std::vector<std::string> up;    // from the netpoint to the centre
    std::vector<std::string> down;  // from the centre to the netpoint
    std::string loopback;           // the netpoint's route to itself, if any
  };
  std::size_t zone = 0;
  std::vector<std::pair<std::string, Ways>> ways;  // by netpoint id, in order of declaration
  std::string router;                              // the zone's gateway, if any
};

enum class SgTopology { Flat, Torus, FatTree, Dragonfly };

/// A <cluster>: its hosts and links are in SgPlatform::hosts and ::links, its routes are
/// computed: a FLAT one's by route_links, the others' by sg_topology_route (formats/simgrid/routing/topology.hpp).
struct SgCluster {
  std::string id;
  SgTopology topology = SgTopology::Flat;
  std::vector<unsigned> topology_parameters;  // topo_parameters' numbers in order
  std::size_t link_serial = 0;                // FAT_TREE, DRAGONFLY: SimGrid's number of its first link
  long position_base = 0;                     // FAT_TREE: SimGrid's position of its first node
  std::size_t first_host = 0;  // node k is SgPlatform::hosts[first_host + k]
  std::vector<int> radicals;   // node k is named prefix + radicals[k] + suffix
  bool split_duplex = true;    // private links are SPLITDUPLEX (_UP and _DOWN halves)
  bool backbone = false;
  bool limiter = false;
  bool loopback = false;
  std::string router;          // its gateway: router_id, else prefix + id + "_router" + suffix
  std::size_t zone = 0;        // the zone it is
  int line = 0;

  std::size_t size() const { return radicals.size(); }
  /// The links from node `from` to node `to` (indices into radicals), as SimGrid's star
  /// routing gives them: the loopback when from == to and there is one; else the source's
  /// way_up then the destination's way_down, a link met twice taken once.
  std::vector<std::string> route_links(std::size_t from, std::size_t to) const;
  /// Node k's links to the cluster's centre: limiter, private link (or its _UP half), backbone.
  std::vector<std::string> way_up(std::size_t k) const;
  /// Node k's links from the centre: backbone, private link (or its _DOWN half), limiter.
  std::vector<std::string> way_down(std::size_t k) const;
};

namespace detail {
struct SgLookup;
}

struct SgPlatform {
  std::string file;
  std::vector<SgZone> zones;          // zones[0] the root; a <cluster> is a zone too
  std::vector<SgRouter> routers;      // document order, a cluster's own router included
  std::vector<SgRoute> zone_routes;   // declared routes not in `routes`: with a router or zone at an end, or in a zone not Full
  std::vector<SgRoute> bypass_routes; // <bypassRoute>s and <bypassZoneRoute>s, oriented, never symmetrical
  std::vector<SgStar> stars;          // <zone routing="Cluster">s' stars
  std::string version;                // "4" or "4.1"
  std::vector<SgHost> hosts;          // document order (clusters expanded in radical order)
  std::vector<SgLink> links;          // document order
  std::vector<SgRoute> routes;        // the <route>s between hosts of Full zones in document order, as written (a symmetrical one once)
  std::vector<SgCluster> clusters;    // document order; their routes are not in `routes`
  std::vector<std::string> warnings;  // "file:line: ..." for things ignored because they cannot change a result

  SgPlatform();

  const SgHost* find_host(std::string_view id) const;
  const SgLink* find_link(std::string_view id) const;
  /// The route from host a to host b, oriented from a to b (src == a, dst == b, links in that
  /// order), or nullptr: a <route> as written, the reverse of a symmetrical one, a route
  /// within a cluster, or SimGrid's route through the zone tree (SgRouteFinder); nullptr also
  /// when SimGrid's rules find no link (a None zone). For a == b, the host's route to itself if the file gives one (a
  /// <route> from the host to itself, or within a cluster); nullptr means none was declared
  /// (SimGrid would then use its network model's loopback). Routes that are not as written
  /// are built on first request and kept (a few hundred bytes each; an O(1) look-up of about
  /// a microsecond once built): the pointer stays valid until build_index(), a change to the
  /// platform, or the destruction of the platform and of its copies, which share them. Safe
  /// to call from several threads at once.
  const SgRoute* find_route(std::string_view a, std::string_view b) const;

  /// Calls `visit` for every route: those of `routes` as written, then for each cluster one
  /// symmetrical route per pair of its nodes (lower index as src) and one per node to itself.
  /// A cluster of n nodes gives n(n + 1)/2 calls: 5050 for 100 nodes, 5 * 10^9 for 10^5.
  /// A platform with routes that are not written as such (is_routed()) lists instead, for
  /// each pair of hosts a, b (a before b, a == b included), the route from a to b when there
  /// is one, symmetrical if the route back is its reverse, and else the route back too.
  void for_each_route(const std::function<void(const SgRoute&)>& visit) const;

  /// The first `most` routes for_each_route lists, the others not visited.
  std::vector<SgRoute> first_routes(std::size_t most) const;

  /// True when a route may be other than a <route> as written or a FLAT cluster's: a zone
  /// routed otherwise than Full, None or as a <cluster>, a route through a router or
  /// between zones, a bypass.
  bool is_routed() const;

  /// How many routes for_each_route lists, without listing them (counted for a routed
  /// platform only when it has at most `most_hosts` hosts; else 0).
  std::size_t route_count(std::size_t most_hosts = 1000) const;

  /// Rebuilds the hash tables behind find_host, find_link and find_route (read_simgrid_platform
  /// calls it). After hosts, links, routes or clusters change, call it again: until then the
  /// find functions search the vectors one by one if their sizes changed, and may miss
  /// changes that keep the sizes.
  void build_index();

 private:
  void visit_routes(const std::function<bool(const SgRoute&)>& visit) const;  // stops when visit returns false

  std::shared_ptr<detail::SgLookup> lookup_;
};

/// Bounds on what a platform file may ask for, so that a few bytes cannot ask for unbounded
/// memory (a radical "0-999999999").
struct SgLimits {
  std::size_t max_cluster_hosts = 100'000;
  std::size_t max_hosts = 1'000'000;  // in the whole platform
};

/// Parses SimGrid platform XML. Throws pagecache::ConfigError whose message is
/// "FILE:LINE: <element> ...: problem" naming the file, the line, the element and attribute
/// at fault.
SgPlatform read_simgrid_platform(const std::string& text, const std::string& file);
SgPlatform read_simgrid_platform(const std::string& text, const std::string& file, const SgLimits& limits);

}  // namespace pagecache::formats::simgrid
