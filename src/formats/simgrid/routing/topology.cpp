// TORUS, FAT_TREE and DRAGONFLY clusters: what they are made of and how they route, by the
// rules of SimGrid's TorusZone, FatTreeZone and DragonflyZone.

#include "formats/simgrid/routing/topology.hpp"

#include <pagecache/error.hpp>

#include <fmt/format.h>

#include <charconv>
#include <string_view>

namespace pagecache::formats::simgrid {

namespace {

// topo_parameters' numbers bounded so that their products stay far from overflow.
constexpr unsigned long kMostParameter = 1'000'000;

std::vector<std::string_view> split(std::string_view text, char by) {
  std::vector<std::string_view> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t at = text.find(by, start);
    parts.push_back(text.substr(start, at == std::string_view::npos ? std::string_view::npos : at - start));
    if (at == std::string_view::npos) return parts;
    start = at + 1;
  }
}

unsigned positive(std::string_view text) {
  while (!text.empty() && text.front() == ' ') text.remove_prefix(1);
  while (!text.empty() && text.back() == ' ') text.remove_suffix(1);
  unsigned long value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || value == 0 || value > kMostParameter) {
    throw ConfigError(fmt::format("'{}' is not a whole number from 1 to {}", text, kMostParameter));
  }
  return static_cast<unsigned>(value);
}

std::size_t product(const std::vector<unsigned>& factors, std::size_t first, std::size_t last) {
  std::size_t p = 1;
  for (std::size_t i = first; i < last; ++i) {
    p *= factors[i];
    if (p > kMostParameter) throw ConfigError(fmt::format("more than {} elements", kMostParameter));
  }
  return p;
}

bool split_duplex(const SgCluster& c) { return c.split_duplex; }
std::string up_of(const SgCluster& c, const std::string& id) { return split_duplex(c) ? id + "_UP" : id; }
std::string down_of(const SgCluster& c, const std::string& id) { return split_duplex(c) ? id + "_DOWN" : id; }
std::string limiter_of(const SgCluster& c, std::size_t number) { return c.id + "_link_" + std::to_string(number) + "_limiter"; }
std::string loopback_of(const SgCluster& c, std::size_t node) { return c.id + "_link_" + std::to_string(c.radicals.at(node)) + "_loopback"; }

// Each node's loopback then limiter, SimGrid's fill_leaf_from_cb.
void add_leaf_links(const SgCluster& c, std::size_t node, std::vector<SgTopologyLink>& links) {
  if (c.loopback) links.push_back({loopback_of(c, node), SgTopologyLink::Kind::Loopback, 1.0});
  if (c.limiter) links.push_back({limiter_of(c, node), SgTopologyLink::Kind::Limiter, 1.0});
}

void add_private(const SgCluster& c, const std::string& id, double factor, std::vector<SgTopologyLink>& links) {
  if (split_duplex(c)) {
    links.push_back({id + "_UP", SgTopologyLink::Kind::Private, factor});
    links.push_back({id + "_DOWN", SgTopologyLink::Kind::Private, factor});
  } else {
    links.push_back({id, SgTopologyLink::Kind::Private, factor});
  }
}

// Torus: the rank a node's link in dimension `dim` goes to (the next one, wrapping around).
std::size_t torus_neighbour(const std::vector<unsigned>& dims, std::size_t rank, std::size_t dim) {
  std::size_t below = 1;
  for (std::size_t j = 0; j < dim; ++j) below *= dims[j];
  return (rank / below) % dims[dim] == dims[dim] - 1 ? rank - (dims[dim] - 1) * below : rank + below;
}

std::string torus_link(const SgCluster& c, std::size_t rank, std::size_t dim) {
  return c.id + "_link_from_" + std::to_string(rank) + "_to_" + std::to_string(torus_neighbour(c.topology_parameters, rank, dim));
}

// SimGrid's dimension-order routing: the first dimension where the nodes differ, rightwards
// (up links) when the target is within half the ring on the right of the source, else leftwards.
std::vector<std::string> torus_route(const SgCluster& c, std::size_t from, std::size_t to) {
  const std::vector<unsigned>& dims = c.topology_parameters;
  std::vector<std::string> route;
  if (from == to && c.loopback) return {loopback_of(c, from)};
  std::size_t current = from;
  std::size_t steps = 0;
  while (current != to && steps++ <= c.size()) {
    std::size_t next = current, below = 1;
    std::string link;
    for (std::size_t j = 0; j < dims.size(); ++j) {
      const std::size_t d = dims[j];
      const std::size_t mine = (from / below) % d, target = (to / below) % d;
      if ((current / below) % d != (to / below) % d) {
        if ((target > mine && target <= mine + d / 2) || (mine > d / 2 && (mine + d / 2) % d >= target)) {
          next = (current / below) % d == d - 1 ? current + below - below * d : current + below;
          link = up_of(c, torus_link(c, current, j));
        } else {
          next = (current / below) % d == 0 ? current - below + below * d : current - below;
          link = down_of(c, torus_link(c, next, j));
        }
        break;
      }
      below *= d;
    }
    if (c.limiter) route.push_back(limiter_of(c, current));
    route.push_back(link);
    current = next;
  }
  if (current != to) return {};
  if (c.limiter) route.push_back(limiter_of(c, to));
  return route;
}

}  // namespace

std::size_t sg_topology_nodes(SgCluster& c, const std::string& parameters) {
  std::vector<unsigned>& p = c.topology_parameters;
  p.clear();
  if (c.topology == SgTopology::Torus) {
    for (const std::string_view dim : split(parameters, ',')) p.push_back(positive(dim));
    return product(p, 0, p.size());
  }
  const std::vector<std::string_view> parts = split(parameters, ';');
  if (c.topology == SgTopology::FatTree) {
    if (parts.size() != 4) throw ConfigError("a fat tree is 'levels;children per level;parents per level;links per level'");
    const unsigned levels = positive(parts[0]);
    p.push_back(levels);
    for (std::size_t part = 1; part < 4; ++part) {
      const std::vector<std::string_view> counts = split(parts[part], ',');
      if (counts.size() != levels) throw ConfigError(fmt::format("{} levels, but {} numbers in '{}'", levels, counts.size(), parts[part]));
      for (const std::string_view n : counts) p.push_back(positive(n));
    }
    return product(p, 1, 1 + levels);
  }
  if (parts.size() != 4) throw ConfigError("a dragonfly is 'groups,links;chassis,links;routers,links;nodes'");
  for (std::size_t part = 0; part < 3; ++part) {
    const std::vector<std::string_view> pair = split(parts[part], ',');
    if (pair.size() != 2) throw ConfigError(fmt::format("'{}' is not two numbers", parts[part]));
    p.push_back(positive(pair[0]));
    p.push_back(positive(pair[1]));
  }
  p.push_back(positive(parts[3]));
  return product({p[0], p[2], p[4], p[6]}, 0, 4);
}

double sg_topology_size(const SgCluster& c) {
  const std::vector<unsigned>& p = c.topology_parameters;
  const double nodes = static_cast<double>(c.size());
  if (c.topology == SgTopology::Torus) return nodes * static_cast<double>(p.size());
  if (c.topology == SgTopology::FatTree) {
    const unsigned levels = p.at(0);
    double size = 0;
    for (unsigned i = 0; i < levels; ++i) {
      // Level i's nodes (switches above 0) each have up[i] x count[i] links to their parents.
      double at_level = 1;
      for (unsigned j = 0; j < levels; ++j) at_level *= j < i ? p[1 + levels + j] : p[1 + j];
      size += at_level * (1.0 + static_cast<double>(p[1 + levels + i]) * p[1 + 2 * levels + i]);
    }
    return size;
  }
  const double groups = p.at(0), chassis = p.at(2), blades = p.at(4);
  const double routers = groups * chassis * blades;
  return routers + nodes + routers * blades / 2 + routers * chassis / 2 + groups * groups / 2;
}

std::vector<SgTopologyLink> sg_topology_links(const SgCluster& c) {
  std::vector<SgTopologyLink> links;
  if (c.topology == SgTopology::Torus) {
    for (std::size_t node = 0; node < c.size(); ++node) {
      add_leaf_links(c, node, links);
      for (std::size_t j = 0; j < c.topology_parameters.size(); ++j) add_private(c, torus_link(c, node, j), 1.0, links);
    }
    return links;
  }
  for (std::size_t node = 0; node < c.size(); ++node) add_leaf_links(c, node, links);
  if (c.topology == SgTopology::FatTree) {
    const SgFatTree tree = sg_fat_tree(c);
    for (std::size_t n = c.size(); n < tree.nodes.size(); ++n) {
      if (!tree.nodes[n].limiter.empty()) links.push_back({tree.nodes[n].limiter, SgTopologyLink::Kind::Limiter, 1.0});
    }
    for (const SgFatTree::Link& l : tree.links) {
      links.push_back({l.up, SgTopologyLink::Kind::Private, 1.0});
      if (l.down != l.up) links.push_back({l.down, SgTopologyLink::Kind::Private, 1.0});
    }
    return links;
  }
  const SgDragonfly fly = sg_dragonfly(c);
  for (const SgDragonfly::Router& r : fly.routers) {
    if (!r.limiter.empty()) links.push_back({r.limiter, SgTopologyLink::Kind::Limiter, 1.0});
  }
  links.insert(links.end(), fly.links.begin(), fly.links.end());
  return links;
}

std::vector<std::string> sg_topology_route(const SgCluster& c, const SgFatTree* tree, const SgDragonfly* fly, std::size_t from, std::size_t to) {
  if (from >= c.size() || to >= c.size()) return {};
  switch (c.topology) {
    case SgTopology::Torus: return torus_route(c, from, to);
    case SgTopology::FatTree: return tree == nullptr ? std::vector<std::string>{} : sg_fat_tree_route(c, *tree, from, to);
    case SgTopology::Dragonfly: return fly == nullptr ? std::vector<std::string>{} : sg_dragonfly_route(c, *fly, from, to);
    case SgTopology::Flat: return c.route_links(from, to);
  }
  return {};
}

}  // namespace pagecache::formats::simgrid
