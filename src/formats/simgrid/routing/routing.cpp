// SimGrid's global route over the zone tree (NetZoneImpl::get_global_route and
// get_bypass_route), and the local routes of Full, Cluster and None zones.

#include "formats/simgrid/routing/routing.hpp"

#include "formats/simgrid/routing/shortest.hpp"

#include <algorithm>

namespace pagecache::formats::simgrid {

namespace {

// Gateways lead to gateways: bounded, so that a platform whose gateways loop cannot recurse forever.
constexpr int kMaxDepth = 128;

std::uint64_t pair_key(std::size_t a, std::size_t b) { return (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint64_t>(b); }

// A netpoint as a number unique in the platform (indices stay below 2^30: SgLimits).
std::size_t code(SgNetpoint n) { return (static_cast<std::size_t>(n.kind) << 30) | n.index; }

// `add` after `links`, a link already there skipped (SimGrid's star never crosses a link twice).
void add_once(std::vector<std::string>& links, const std::vector<std::string>& add) {
  for (const std::string& l : add) {
    if (std::find(links.begin(), links.end(), l) == links.end()) links.push_back(l);
  }
}

}  // namespace

SgRouteFinder::SgRouteFinder(const SgPlatform& p) {
  const std::size_t zones = p.zones.size();
  host_vertex_.assign(p.hosts.size(), 0);
  router_vertex_.assign(p.routers.size(), 0);
  zone_vertex_.assign(zones, 0);
  recursive_.assign(zones, false);
  members_.assign(zones, 0);
  for (std::size_t z = 0; z < zones; ++z) {
    const SgZone& zone = p.zones[z];
    members_[z] = zone.members.size();
    for (std::size_t v = 0; v < zone.members.size(); ++v) {
      const SgNetpoint n = zone.members[v];
      if (n.kind == SgNetpoint::Kind::Host) host_vertex_[n.index] = v;
      if (n.kind == SgNetpoint::Kind::Router) router_vertex_[n.index] = v;
      if (n.kind == SgNetpoint::Kind::Zone) {
        zone_vertex_[n.index] = v;
        recursive_[z] = true;
      }
    }
  }
  for (std::size_t i = 0; i < p.hosts.size(); ++i) netpoint_at_.emplace(p.hosts[i].id, SgNetpoint{SgNetpoint::Kind::Host, i});
  for (std::size_t i = 0; i < p.routers.size(); ++i) netpoint_at_.emplace(p.routers[i].id, SgNetpoint{SgNetpoint::Kind::Router, i});
  for (std::size_t i = 0; i < zones; ++i) netpoint_at_.emplace(p.zones[i].id, SgNetpoint{SgNetpoint::Kind::Zone, i});

  edges_.resize(zones);
  edge_at_.resize(zones);
  const auto add_edges = [&](const std::vector<SgRoute>& routes, bool written) {
    for (std::size_t i = 0; i < routes.size(); ++i) {
      const SgRoute& r = routes[i];
      const auto src = netpoint(r.src);
      const auto dst = netpoint(r.dst);
      if (!src || !dst || r.zone >= zones) continue;
      const std::size_t from = vertex(*src), to = vertex(*dst);
      edges_[r.zone].push_back({from, to, {i, written, false}, r.line, r.links.size()});
      edge_at_[r.zone].emplace(pair_key(from, to), SgEdge{i, written, false});
      if (r.symmetrical && from != to) {
        edges_[r.zone].push_back({to, from, {i, written, true}, r.line, r.links.size()});
        edge_at_[r.zone].emplace(pair_key(to, from), SgEdge{i, written, true});
      }
    }
  };
  // Document order: the reader keeps each zone's routes of both vectors in the order declared.
  add_edges(p.routes, true);
  add_edges(p.zone_routes, false);
  for (auto& zone_edges : edges_) {
    std::stable_sort(zone_edges.begin(), zone_edges.end(), [](const ZoneEdge& a, const ZoneEdge& b) { return a.line < b.line; });
  }
  bypass_at_.resize(zones);
  for (std::size_t i = 0; i < p.bypass_routes.size(); ++i) {
    const SgRoute& r = p.bypass_routes[i];
    const auto src = netpoint(r.src);
    const auto dst = netpoint(r.dst);
    if (src && dst && r.zone < zones) bypass_at_[r.zone].emplace(pair_key(code(*src), code(*dst)), i);
  }
  star_ways_.resize(zones);
  for (std::size_t s = 0; s < p.stars.size(); ++s) {
    if (p.stars[s].zone >= zones) continue;
    for (std::size_t w = 0; w < p.stars[s].ways.size(); ++w) star_ways_[p.stars[s].zone].emplace(p.stars[s].ways[w].first, std::pair{s, w});
  }
  shortest_ = std::make_unique<Shortest>(*this);
  trees_.resize(p.clusters.size());
  flies_.resize(p.clusters.size());
  for (std::size_t c = 0; c < p.clusters.size(); ++c) {
    if (p.clusters[c].topology == SgTopology::FatTree) trees_[c] = std::make_unique<SgFatTree>(sg_fat_tree(p.clusters[c]));
    if (p.clusters[c].topology == SgTopology::Dragonfly) flies_[c] = std::make_unique<SgDragonfly>(sg_dragonfly(p.clusters[c]));
  }
}

SgRouteFinder::~SgRouteFinder() = default;

std::optional<SgNetpoint> SgRouteFinder::netpoint(const std::string& id) const {
  const auto it = netpoint_at_.find(id);
  if (it == netpoint_at_.end()) return std::nullopt;
  return it->second;
}

std::size_t SgRouteFinder::vertex(SgNetpoint n) const {
  switch (n.kind) {
    case SgNetpoint::Kind::Host: return host_vertex_[n.index];
    case SgNetpoint::Kind::Router: return router_vertex_[n.index];
    case SgNetpoint::Kind::Zone: return zone_vertex_[n.index];
  }
  return 0;
}

std::size_t SgRouteFinder::zone_of(const SgPlatform& p, SgNetpoint n) const {
  switch (n.kind) {
    case SgNetpoint::Kind::Host: return p.hosts[n.index].zone;
    case SgNetpoint::Kind::Router: return p.routers[n.index].zone;
    case SgNetpoint::Kind::Zone: return p.zones[n.index].parent;
  }
  return kNoZone;
}

std::vector<std::size_t> SgRouteFinder::zones_from_root(const SgPlatform& p, SgNetpoint n) const {
  std::vector<std::size_t> path;
  for (std::size_t z = zone_of(p, n); z < p.zones.size() && path.size() <= p.zones.size(); z = p.zones[z].parent) path.push_back(z);
  std::reverse(path.begin(), path.end());
  return path;
}

const SgEdge* SgRouteFinder::edge(std::size_t zone, std::size_t from, std::size_t to) const {
  const auto it = edge_at_[zone].find(pair_key(from, to));
  return it == edge_at_[zone].end() ? nullptr : &it->second;
}

SgLocalRoute SgRouteFinder::local_of(const SgPlatform& p, const SgEdge& e) const {
  SgLocalRoute out;
  const SgRoute& r = e.of(p);
  if (!e.reversed) {
    out.links = r.links;
  } else {
    for (auto link = r.links.rbegin(); link != r.links.rend(); ++link) {
      const SgLink* l = p.find_link(*link);
      out.links.push_back(l != nullptr && l->half != DuplexHalf::None ? l->duplex_id + (l->half == DuplexHalf::Up ? "_DOWN" : "_UP") : *link);
    }
  }
  if (!r.gw_src.empty()) out.gw_src = netpoint(e.reversed ? r.gw_dst : r.gw_src);
  if (!r.gw_dst.empty()) out.gw_dst = netpoint(e.reversed ? r.gw_src : r.gw_dst);
  return out;
}

bool SgRouteFinder::host_route(const SgPlatform& p, std::size_t a, std::size_t b, std::vector<std::string>& links) const {
  links.clear();
  const bool found = global(p, {SgNetpoint::Kind::Host, a}, {SgNetpoint::Kind::Host, b}, links, 0);
  return found && !links.empty();
}

bool SgRouteFinder::global(const SgPlatform& p, SgNetpoint src, SgNetpoint dst, std::vector<std::string>& links, int depth) const {
  if (depth > kMaxDepth) return false;
  const std::vector<std::size_t> src_path = zones_from_root(p, src);
  const std::vector<std::size_t> dst_path = zones_from_root(p, dst);
  if (src_path.empty() || dst_path.empty() || src_path.front() != dst_path.front()) return false;
  std::size_t i = 0;
  while (i + 1 < src_path.size() && i + 1 < dst_path.size() && src_path[i + 1] == dst_path[i + 1]) ++i;
  const std::size_t common = src_path[i];
  const std::size_t src_ancestor = i + 1 < src_path.size() ? src_path[i + 1] : common;
  const std::size_t dst_ancestor = i + 1 < dst_path.size() ? dst_path[i + 1] : common;

  if (bypass(p, common, src, dst, links, depth)) return true;
  SgLocalRoute route;
  const SgNetpoint from = src_ancestor != common ? SgNetpoint{SgNetpoint::Kind::Zone, src_ancestor} : src;
  const SgNetpoint to = dst_ancestor != common ? SgNetpoint{SgNetpoint::Kind::Zone, dst_ancestor} : dst;
  if (!local(p, common, from, to, route, depth)) return false;
  if (src_ancestor != common) {
    if (!route.gw_src) return false;
    if (!(*route.gw_src == src) && !global(p, src, *route.gw_src, links, depth + 1)) return false;
  }
  links.insert(links.end(), route.links.begin(), route.links.end());
  if (dst_ancestor != common) {
    if (!route.gw_dst) return false;
    if (!(*route.gw_dst == dst) && !global(p, *route.gw_dst, dst, links, depth + 1)) return false;
  }
  return true;
}

// SimGrid's get_bypass_route: in the zone itself, the bypass between the two netpoints; else the
// first bypass between zones on their ways up, the nearest to them first.
bool SgRouteFinder::bypass(const SgPlatform& p, std::size_t common, SgNetpoint src, SgNetpoint dst, std::vector<std::string>& links, int depth) const {
  const auto& bypasses = bypass_at_[common];
  if (bypasses.empty()) return false;
  if (zone_of(p, src) == common && zone_of(p, dst) == common) {
    const auto it = bypasses.find(pair_key(code(src), code(dst)));
    if (it == bypasses.end()) return false;
    const SgRoute& r = p.bypass_routes[it->second];
    links.insert(links.end(), r.links.begin(), r.links.end());
    return true;
  }
  // The zones from each netpoint's up to the root, without the part they share (one kept).
  std::vector<std::size_t> up_src = zones_from_root(p, src), up_dst = zones_from_root(p, dst);
  std::reverse(up_src.begin(), up_src.end());
  std::reverse(up_dst.begin(), up_dst.end());
  while (up_src.size() > 1 && up_dst.size() > 1 && up_src.back() == up_dst.back()) up_src.pop_back(), up_dst.pop_back();
  const SgRoute* found = nullptr;
  const auto lookup = [&](std::size_t i, std::size_t j) {
    if (i >= up_src.size() || j >= up_dst.size()) return false;
    const auto it = bypasses.find(pair_key(code({SgNetpoint::Kind::Zone, up_src[i]}), code({SgNetpoint::Kind::Zone, up_dst[j]})));
    if (it == bypasses.end()) return false;
    found = &p.bypass_routes[it->second];
    return true;
  };
  for (std::size_t most = 0, last = std::max(up_src.size(), up_dst.size()); most < last; ++most) {
    for (std::size_t i = 0; i < most; ++i) {
      if (lookup(i, most) || lookup(most, i)) break;
    }
    if (found != nullptr || lookup(most, most)) break;
  }
  if (found == nullptr) return false;
  const auto gw_src = netpoint(found->gw_src);
  const auto gw_dst = netpoint(found->gw_dst);
  if (!gw_src || !gw_dst) return false;
  // A gateway that is the netpoint itself needs no route to it (SimGrid would add its model's loopback).
  if (!(*gw_src == src) && !global(p, src, *gw_src, links, depth + 1)) return false;
  links.insert(links.end(), found->links.begin(), found->links.end());
  return *gw_dst == dst || global(p, *gw_dst, dst, links, depth + 1);
}

bool SgRouteFinder::local(const SgPlatform& p, std::size_t zone, SgNetpoint src, SgNetpoint dst, SgLocalRoute& out, int depth) const {
  switch (p.zones[zone].routing) {
    case SgRouting::Full: {
      const SgEdge* e = edge(zone, vertex(src), vertex(dst));
      if (e == nullptr) return false;
      out = local_of(p, *e);
      return true;
    }
    case SgRouting::Floyd: return shortest_->floyd(p, zone, vertex(src), vertex(dst), out, depth);
    case SgRouting::Dijkstra:
    case SgRouting::DijkstraCache: return shortest_->dijkstra(p, zone, vertex(src), vertex(dst), out);
    case SgRouting::Cluster: return star(p, zone, src, dst, out);
    case SgRouting::None: return true;  // SimGrid's EmptyZone: no link
  }
  return false;
}

// SimGrid's StarZone: the loopback to itself if it has one, else the source's way up then the
// destination's way down, each link once. A netpoint the star has no ways for (a router) adds none.
bool SgRouteFinder::star(const SgPlatform& p, std::size_t zone, SgNetpoint src, SgNetpoint dst, SgLocalRoute& out) const {
  const SgZone& z = p.zones[zone];
  if (src.kind == SgNetpoint::Kind::Zone || dst.kind == SgNetpoint::Kind::Zone) return false;
  if (z.cluster != kNoZone) {
    const SgCluster& c = p.clusters[z.cluster];
    const auto node = [&](SgNetpoint n) -> std::optional<std::size_t> {
      if (n.kind != SgNetpoint::Kind::Host || n.index < c.first_host || n.index - c.first_host >= c.size()) return std::nullopt;
      return n.index - c.first_host;
    };
    const auto from = node(src), to = node(dst);
    if (c.topology != SgTopology::Flat) {
      // SimGrid's topologies route between their nodes only.
      if (from && to) out.links = sg_topology_route(c, trees_[z.cluster].get(), flies_[z.cluster].get(), *from, *to);
      return true;
    }
    if (from && to) {
      out.links = c.route_links(*from, *to);
    } else {
      if (from) out.links = c.way_up(*from);
      if (to) add_once(out.links, c.way_down(*to));
    }
    return true;
  }
  const auto ways = [&](SgNetpoint n) -> const SgStar::Ways* {
    const std::string& id = n.kind == SgNetpoint::Kind::Host ? p.hosts[n.index].id : p.routers[n.index].id;
    const auto it = star_ways_[zone].find(id);
    return it == star_ways_[zone].end() ? nullptr : &p.stars[it->second.first].ways[it->second.second].second;
  };
  const SgStar::Ways* from = ways(src);
  const SgStar::Ways* to = ways(dst);
  if (src == dst && from != nullptr && !from->loopback.empty()) {
    out.links = {from->loopback};
    return true;
  }
  if (from != nullptr) add_once(out.links, from->up);
  if (to != nullptr) add_once(out.links, to->down);
  return true;
}

}  // namespace pagecache::formats::simgrid
