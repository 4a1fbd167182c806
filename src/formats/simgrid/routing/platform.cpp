// SgPlatform's queries: hash tables built once, a linear search when they are out of date, and
// the routes that are not stored as written (reverses, cluster routes) built on request.

#include "formats/simgrid/routing/platform.hpp"

#include "formats/simgrid/routing/routing.hpp"

#include <algorithm>
#include <cstdint>
#include <mutex>
#include <unordered_map>

namespace pagecache::formats::simgrid {

namespace {

// `up` then `down` into `links`, a link met twice taken once (the backbone; for a node to
// itself, its own links). Assigns over `links`' strings, so that a loop reusing it allocates
// little.
void join_ways(const std::vector<std::string>& up, const std::vector<std::string>& down, std::vector<std::string>& links) {
  std::size_t n = 0;
  const auto add = [&](const std::string& link) {
    if (std::find(links.begin(), links.begin() + static_cast<std::ptrdiff_t>(n), link) != links.begin() + static_cast<std::ptrdiff_t>(n)) return;
    if (n < links.size()) {
      links[n] = link;
    } else {
      links.push_back(link);
    }
    ++n;
  };
  for (const std::string& link : up) add(link);
  for (const std::string& link : down) add(link);
  links.resize(n);
}

}  // namespace

std::vector<std::string> SgCluster::way_up(std::size_t k) const {
  const std::string link = id + "_link_" + std::to_string(radicals.at(k));
  std::vector<std::string> way;
  if (limiter) way.push_back(link + "_limiter");
  way.push_back(split_duplex ? link + "_UP" : link);
  if (backbone) way.push_back(id + "_backbone");
  return way;
}

std::vector<std::string> SgCluster::way_down(std::size_t k) const {
  const std::string link = id + "_link_" + std::to_string(radicals.at(k));
  std::vector<std::string> way;
  if (backbone) way.push_back(id + "_backbone");
  way.push_back(split_duplex ? link + "_DOWN" : link);
  if (limiter) way.push_back(link + "_limiter");
  return way;
}

std::vector<std::string> SgCluster::route_links(std::size_t from, std::size_t to) const {
  if (from == to && loopback) return {id + "_link_" + std::to_string(radicals.at(from)) + "_loopback"};
  std::vector<std::string> links;
  join_ways(way_up(from), way_down(to), links);
  return links;
}

namespace detail {

struct NameHash {
  using is_transparent = void;
  std::size_t operator()(std::string_view s) const { return std::hash<std::string_view>{}(s); }
};
using NameMap = std::unordered_map<std::string, std::size_t, NameHash, std::equal_to<>>;

struct SgLookup {
  // The tables, written by build_index only.
  bool built = false;
  std::size_t hosts = 0, links = 0, routes = 0, clusters = 0, zone_routes = 0;  // the sizes they were built for
  NameMap host_at;
  NameMap link_at;
  struct RouteAt {
    std::size_t route;
    bool reversed;
  };
  std::unordered_map<std::uint64_t, RouteAt> route_at;  // by (src, dst) host indices
  std::vector<std::uint32_t> cluster_of;                // per host: its cluster's index + 1, or 0
  // Routes other than as written or a FLAT cluster's: indexed on first need (a run on a cluster never needs it).
  std::once_flag finder_made;
  std::unique_ptr<SgRouteFinder> finder;
  const SgRouteFinder& finder_of(const SgPlatform& p) {
    std::call_once(finder_made, [&] { finder = std::make_unique<SgRouteFinder>(p); });
    return *finder;
  }

  // Routes built on request, by (src, dst) host indices.
  std::mutex mutex;
  std::unordered_map<std::uint64_t, std::unique_ptr<SgRoute>> built_routes;
};

}  // namespace detail

namespace {

std::uint64_t pair_key(std::size_t a, std::size_t b) { return (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint64_t>(b); }

constexpr std::size_t kNone = static_cast<std::size_t>(-1);

template <typename T>
std::size_t position_of(const std::vector<T>& items, std::string_view id) {
  const auto it = std::find_if(items.begin(), items.end(), [id](const T& item) { return item.id == id; });
  return it == items.end() ? kNone : static_cast<std::size_t>(it - items.begin());
}

}  // namespace

SgPlatform::SgPlatform() : lookup_(std::make_shared<detail::SgLookup>()) {}

void SgPlatform::build_index() {
  auto lookup = std::make_shared<detail::SgLookup>();
  for (std::size_t i = 0; i < hosts.size(); ++i) lookup->host_at.emplace(hosts[i].id, i);
  for (std::size_t i = 0; i < links.size(); ++i) lookup->link_at.emplace(links[i].id, i);
  for (std::size_t i = 0; i < routes.size(); ++i) {
    const auto src = lookup->host_at.find(routes[i].src);
    const auto dst = lookup->host_at.find(routes[i].dst);
    if (src == lookup->host_at.end() || dst == lookup->host_at.end()) continue;
    lookup->route_at.emplace(pair_key(src->second, dst->second), detail::SgLookup::RouteAt{i, false});
    if (routes[i].symmetrical && src->second != dst->second) {
      lookup->route_at.emplace(pair_key(dst->second, src->second), detail::SgLookup::RouteAt{i, true});
    }
  }
  lookup->cluster_of.assign(hosts.size(), 0);
  for (std::size_t c = 0; c < clusters.size(); ++c) {
    const SgCluster& cluster = clusters[c];
    for (std::size_t k = 0; k < cluster.size() && cluster.first_host + k < hosts.size(); ++k) {
      lookup->cluster_of[cluster.first_host + k] = static_cast<std::uint32_t>(c + 1);
    }
  }
  lookup->hosts = hosts.size();
  lookup->links = links.size();
  lookup->routes = routes.size();
  lookup->clusters = clusters.size();
  lookup->zone_routes = zone_routes.size() + bypass_routes.size() + zones.size();
  lookup->built = true;
  lookup_ = std::move(lookup);
}

namespace {

bool up_to_date(const detail::SgLookup& lookup, const SgPlatform& p) {
  return lookup.built && lookup.hosts == p.hosts.size() && lookup.links == p.links.size() && lookup.routes == p.routes.size() &&
         lookup.clusters == p.clusters.size() && lookup.zone_routes == p.zone_routes.size() + p.bypass_routes.size() + p.zones.size();
}

std::size_t find_in(const detail::NameMap& map, std::string_view id) {
  const auto it = map.find(id);
  return it == map.end() ? kNone : it->second;
}

}  // namespace

const SgHost* SgPlatform::find_host(std::string_view id) const {
  const std::size_t i = up_to_date(*lookup_, *this) ? find_in(lookup_->host_at, id) : position_of(hosts, id);
  return i == kNone ? nullptr : &hosts[i];
}

const SgLink* SgPlatform::find_link(std::string_view id) const {
  const std::size_t i = up_to_date(*lookup_, *this) ? find_in(lookup_->link_at, id) : position_of(links, id);
  return i == kNone ? nullptr : &links[i];
}

const SgRoute* SgPlatform::find_route(std::string_view a, std::string_view b) const {
  const bool indexed = up_to_date(*lookup_, *this);
  const std::size_t ia = indexed ? find_in(lookup_->host_at, a) : position_of(hosts, a);
  const std::size_t ib = indexed ? find_in(lookup_->host_at, b) : position_of(hosts, b);
  if (ia == kNone || ib == kNone) return nullptr;

  // What the route is made from: a <route> (maybe to reverse), or a cluster's two nodes.
  const SgRoute* written = nullptr;
  bool reversed = false;
  const SgCluster* cluster = nullptr;
  if (indexed) {
    if (const auto it = lookup_->route_at.find(pair_key(ia, ib)); it != lookup_->route_at.end()) {
      written = &routes[it->second.route];
      reversed = it->second.reversed;
    } else if (lookup_->cluster_of[ia] != 0 && lookup_->cluster_of[ia] == lookup_->cluster_of[ib]) {
      cluster = &clusters[lookup_->cluster_of[ia] - 1];
    }
  } else {
    for (const SgRoute& r : routes) {
      if (r.src == a && r.dst == b) {
        written = &r;
        reversed = false;
        break;
      }
      if (written == nullptr && r.symmetrical && r.src == b && r.dst == a) {
        written = &r;
        reversed = true;
      }
    }
    if (written == nullptr) {
      const auto in = [](const SgCluster& c, std::size_t host) { return host >= c.first_host && host - c.first_host < c.size(); };
      const auto it = std::find_if(clusters.begin(), clusters.end(), [&](const SgCluster& c) { return in(c, ia) && in(c, ib); });
      if (it != clusters.end()) cluster = &*it;
    }
  }
  // A bypass may override a route as written or a cluster's: SimGrid looks for one first.
  if (!bypass_routes.empty()) written = nullptr, cluster = nullptr;
  if (cluster != nullptr && cluster->topology != SgTopology::Flat) cluster = nullptr;  // the finder routes topologies
  if (written != nullptr && !reversed) return written;

  std::vector<std::string> found;
  if (written == nullptr && cluster == nullptr) {
    const bool routed = indexed ? lookup_->finder_of(*this).host_route(*this, ia, ib, found) : SgRouteFinder(*this).host_route(*this, ia, ib, found);
    if (!routed) return nullptr;
  }
  const std::lock_guard<std::mutex> hold(lookup_->mutex);
  std::unique_ptr<SgRoute>& route = lookup_->built_routes[pair_key(ia, ib)];
  // Without an index the hosts may have moved since the route was built: then it is built again.
  if (route && route->src == a && route->dst == b) return route.get();
  route = std::make_unique<SgRoute>();
  route->src = std::string(a);
  route->dst = std::string(b);
  if (written != nullptr) {
    route->line = written->line;
    for (auto link = written->links.rbegin(); link != written->links.rend(); ++link) {
      const SgLink* l = find_link(*link);
      if (l != nullptr && l->half != DuplexHalf::None) {
        route->links.push_back(l->duplex_id + (l->half == DuplexHalf::Up ? "_DOWN" : "_UP"));
      } else {
        route->links.push_back(*link);
      }
    }
  } else if (cluster != nullptr) {
    route->line = cluster->line;
    route->symmetrical = ia != ib;
    route->links = cluster->route_links(ia - cluster->first_host, ib - cluster->first_host);
  } else {
    route->line = hosts[ia].line;
    route->symmetrical = false;
    route->links = std::move(found);
  }
  return route.get();
}

bool SgPlatform::is_routed() const {
  return !zone_routes.empty() || !bypass_routes.empty() || !stars.empty() ||
         std::any_of(clusters.begin(), clusters.end(), [](const SgCluster& c) { return c.topology != SgTopology::Flat; });
}

std::size_t SgPlatform::route_count(std::size_t most_hosts) const {
  if (is_routed()) {
    if (hosts.size() > most_hosts) return 0;
    std::size_t n = 0;
    for_each_route([&](const SgRoute&) { ++n; });
    return n;
  }
  std::size_t n = routes.size();
  for (const SgCluster& c : clusters) n += c.size() * (c.size() + 1) / 2;
  return n;
}

namespace {

// The routes of a routed platform, pair by pair: none kept, so that a listing costs no memory.
bool for_each_routed(const SgPlatform& p, const SgRouteFinder& finder, const std::function<bool(const SgRoute&)>& visit) {
  SgRoute there, back;
  for (std::size_t a = 0; a < p.hosts.size(); ++a) {
    for (std::size_t b = a; b < p.hosts.size(); ++b) {
      const bool found = finder.host_route(p, a, b, there.links);
      const bool found_back = a != b && finder.host_route(p, b, a, back.links);
      bool reverse = found && found_back && there.links.size() == back.links.size();
      for (std::size_t i = 0; reverse && i < there.links.size(); ++i) {
        const SgLink* l = p.find_link(there.links[i]);
        const std::string& mirror = back.links[back.links.size() - 1 - i];
        reverse = l != nullptr && (l->half == DuplexHalf::None ? mirror == l->id : mirror == l->duplex_id + (l->half == DuplexHalf::Up ? "_DOWN" : "_UP"));
      }
      if (found) {
        there.src = p.hosts[a].id, there.dst = p.hosts[b].id, there.line = p.hosts[a].line, there.symmetrical = reverse;
        if (!visit(there)) return false;
      }
      if (found_back && !reverse) {
        back.src = p.hosts[b].id, back.dst = p.hosts[a].id, back.line = p.hosts[b].line, back.symmetrical = false;
        if (!visit(back)) return false;
      }
    }
  }
  return true;
}

}  // namespace

void SgPlatform::for_each_route(const std::function<void(const SgRoute&)>& visit) const {
  visit_routes([&](const SgRoute& r) {
    visit(r);
    return true;
  });
}

std::vector<SgRoute> SgPlatform::first_routes(std::size_t most) const {
  std::vector<SgRoute> first;
  if (most == 0) return first;
  visit_routes([&](const SgRoute& r) {
    first.push_back(r);
    return first.size() < most;
  });
  return first;
}

void SgPlatform::visit_routes(const std::function<bool(const SgRoute&)>& visit) const {
  if (is_routed()) {
    if (up_to_date(*lookup_, *this)) {
      for_each_routed(*this, lookup_->finder_of(*this), visit);
    } else {
      for_each_routed(*this, SgRouteFinder(*this), visit);
    }
    return;
  }
  for (const SgRoute& r : routes) {
    if (!visit(r)) return;
  }
  SgRoute route;
  for (const SgCluster& cluster : clusters) {
    const std::size_t n = std::min(cluster.size(), hosts.size() - std::min(hosts.size(), cluster.first_host));
    // Each node's ways, built once: the n(n + 1)/2 routes are then joined from them.
    std::vector<std::vector<std::string>> up(n);
    std::vector<std::vector<std::string>> down(n);
    for (std::size_t k = 0; k < n; ++k) {
      up[k] = cluster.way_up(k);
      down[k] = cluster.way_down(k);
    }
    route.line = cluster.line;
    for (std::size_t i = 0; i < n; ++i) {
      route.src = hosts[cluster.first_host + i].id;
      for (std::size_t j = i; j < n; ++j) {
        route.dst = hosts[cluster.first_host + j].id;
        route.symmetrical = i != j;
        if (i == j && cluster.loopback) {
          route.links = cluster.route_links(i, i);
        } else {
          join_ways(up[i], down[j], route.links);
        }
        if (!visit(route)) return;
      }
    }
  }
}

}  // namespace pagecache::formats::simgrid
