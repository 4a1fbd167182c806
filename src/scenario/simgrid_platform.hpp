#pragma once
// A SimGrid platform file (XML, DTD versions 4 and 4.1) read into plain structs, for pcsim to
// build its own platform from: hosts (speed, cores, properties, disks), network links, and the
// routes between hosts as ordered lists of link ids. Everything that can change a simulation
// result is read and checked; what pcsim cannot represent (routing other than Full, routes
// between zones, traces, WIFI links) is refused with ConfigError naming the file, line,
// element and attribute; what cannot change a result is ignored with a warning.
//
// Units are SimGrid's (simgrid_units.hpp), stored in SI: bandwidths in bytes/s, latencies in
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
// a <cluster>_backbone if bb_bw is given. Its n(n - 1) routes are not stored: SgCluster
// computes one on request (SimGrid's star routing), find_route returns it and for_each_route
// lists them all.

#include <pagecache/error.hpp>

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace pagecache::scenario {

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

struct SgHost {
  std::string id;
  double speed = 0;  // flop/s, of the pstate the host starts in (attribute pstate, default 0)
  int cores = 1;
  SgProps props;     // in document order; a cluster's props are given to each of its hosts
  std::vector<SgDisk> disks;
  std::string cluster;  // the id of the <cluster> that made this host, else empty
  int line = 0;
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
};

/// A FLAT <cluster>: its hosts and links are in SgPlatform::hosts and ::links, its routes are
/// computed by route_links.
struct SgCluster {
  std::string id;
  std::size_t first_host = 0;  // node k is SgPlatform::hosts[first_host + k]
  std::vector<int> radicals;   // node k is named prefix + radicals[k] + suffix
  bool split_duplex = true;    // private links are SPLITDUPLEX (_UP and _DOWN halves)
  bool backbone = false;
  bool limiter = false;
  bool loopback = false;
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
  std::string version;                // "4" or "4.1"
  std::vector<SgHost> hosts;          // document order (clusters expanded in radical order)
  std::vector<SgLink> links;          // document order
  std::vector<SgRoute> routes;        // the <route>s in document order, as written (a symmetrical one once)
  std::vector<SgCluster> clusters;    // document order; their routes are not in `routes`
  std::vector<std::string> warnings;  // "file:line: ..." for things ignored because they cannot change a result

  SgPlatform();

  const SgHost* find_host(std::string_view id) const;
  const SgLink* find_link(std::string_view id) const;
  /// The route from host a to host b, oriented from a to b (src == a, dst == b, links in that
  /// order), or nullptr: a <route> as written, the reverse of a symmetrical one, or a route
  /// within a cluster. For a == b, the host's route to itself if the file gives one (a
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
  void for_each_route(const std::function<void(const SgRoute&)>& visit) const;

  /// Rebuilds the hash tables behind find_host, find_link and find_route (read_simgrid_platform
  /// calls it). After hosts, links, routes or clusters change, call it again: until then the
  /// find functions search the vectors one by one if their sizes changed, and may miss
  /// changes that keep the sizes.
  void build_index();

 private:
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

}  // namespace pagecache::scenario
