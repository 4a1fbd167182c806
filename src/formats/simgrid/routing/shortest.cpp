// Floyd and Dijkstra zones' routes, as SimGrid's FloydZone and DijkstraZone compute them.

#include "formats/simgrid/routing/shortest.hpp"

#include <climits>
#include <queue>
#include <utility>

namespace pagecache::formats::simgrid {

namespace {

constexpr std::uint64_t kInfinite = ULONG_MAX;  // SimGrid's, whose sums wrap as unsigned long

}  // namespace

const SgRouteFinder::Shortest::FloydTables& SgRouteFinder::Shortest::floyd_tables(std::size_t zone) {
  std::unique_ptr<FloydTables>& tables = floyd_[zone];
  if (tables) return *tables;
  tables = std::make_unique<FloydTables>();
  FloydTables& t = *tables;
  const std::size_t n = t.n = finder_.members(zone);
  t.cost.assign(n * n, kInfinite);
  t.pred.assign(n * n, -1);
  t.loopback.assign(n, false);
  for (const ZoneEdge& e : finder_.edges_of(zone)) {
    t.pred[e.from * n + e.to] = static_cast<long>(e.from);
    t.cost[e.from * n + e.to] = e.links;
  }
  if (!finder_.recursive(zone)) {
    for (std::size_t i = 0; i < n; ++i) {
      if (t.pred[i * n + i] != -1) continue;
      t.loopback[i] = true;
      t.pred[i * n + i] = static_cast<long>(i);
      t.cost[i * n + i] = 1;
    }
  }
  for (std::size_t c = 0; c < n; ++c) {
    for (std::size_t a = 0; a < n; ++a) {
      const std::uint64_t ac = t.cost[a * n + c];
      if (ac == kInfinite) continue;
      for (std::size_t b = 0; b < n; ++b) {
        const std::uint64_t cb = t.cost[c * n + b];
        std::uint64_t& ab = t.cost[a * n + b];
        if (cb < kInfinite && (ab == kInfinite || ac + cb < ab)) {
          ab = ac + cb;
          t.pred[a * n + b] = t.pred[c * n + b];
        }
      }
    }
  }
  return t;
}

bool SgRouteFinder::Shortest::floyd(const SgPlatform& p, std::size_t zone, std::size_t from, std::size_t to, SgLocalRoute& out, int depth) {
  if (finder_.members(zone) > kFloydMost) return dijkstra(p, zone, from, to, out);
  std::vector<SgLocalRoute> hops;  // from the last to the first
  {
    const std::lock_guard<std::mutex> hold(mutex_);
    const FloydTables& t = floyd_tables(zone);
    if (from == to && t.loopback[from]) return false;
    std::size_t cur = to;
    do {
      const long pred = t.pred[from * t.n + cur];
      if (pred < 0 || hops.size() > t.n) return false;
      const SgEdge* e = finder_.edge(zone, static_cast<std::size_t>(pred), cur);
      if (e == nullptr) return false;
      hops.push_back(finder_.local_of(p, *e));
      cur = static_cast<std::size_t>(pred);
    } while (cur != from);
  }
  const bool recursive = finder_.recursive(zone);
  if (recursive) {
    out.gw_src = hops.back().gw_src;
    out.gw_dst = hops.front().gw_dst;
  }
  std::optional<SgNetpoint> previous_gw;
  for (auto hop = hops.rbegin(); hop != hops.rend(); ++hop) {
    // Two routes between zones meet at different gateways: the route between those joins them.
    if (recursive && previous_gw && hop->gw_src && !(*previous_gw == *hop->gw_src) && !finder_.global(p, *previous_gw, *hop->gw_src, out.links, depth + 1)) {
      return false;
    }
    out.links.insert(out.links.end(), hop->links.begin(), hop->links.end());
    previous_gw = hop->gw_dst;
  }
  return true;
}

SgRouteFinder::Shortest::Graph& SgRouteFinder::Shortest::graph(std::size_t zone) {
  Graph& g = dijkstra_[zone];
  if (g.built) return g;
  g.built = true;
  const auto node = [&](std::size_t vertex) {
    const auto [it, added] = g.id_of.emplace(vertex, g.vertex_of.size());
    if (added) {
      g.vertex_of.push_back(vertex);
      g.out.emplace_back();
    }
    return it->second;
  };
  for (const ZoneEdge& e : finder_.edges_of(zone)) {
    const std::size_t a = node(e.from);
    const std::size_t b = node(e.to);
    g.out[a].push_back({b, e.links, false});
  }
  if (!finder_.recursive(zone)) {
    for (std::size_t i = 0; i < g.out.size(); ++i) {
      bool self = false;
      for (const Graph::Arc& arc : g.out[i]) self = self || arc.to == i;
      if (!self) g.out[i].push_back({i, 1, true});
    }
  }
  return g;
}

// SimGrid's loop as it is: every vertex queued at the start, no vertex marked done, costs
// that wrap past ULONG_MAX; ties taken by the lower graph id.
const std::vector<std::size_t>& SgRouteFinder::Shortest::predecessors(Graph& g, std::size_t src) {
  const auto [it, added] = g.pred_from.try_emplace(src);
  std::vector<std::size_t>& pred = it->second;
  if (!added) return pred;
  const std::size_t n = g.vertex_of.size();
  std::vector<std::uint64_t> cost(n, kInfinite);
  pred.assign(n, 0);
  cost[src] = 0;
  using Entry = std::pair<double, std::size_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
  for (std::size_t i = 0; i < n; ++i) queue.emplace(static_cast<double>(cost[i]), i);
  while (!queue.empty()) {
    const std::size_t v = queue.top().second;
    queue.pop();
    for (const Graph::Arc& arc : g.out[v]) {
      if (arc.weight + cost[v] < cost[arc.to]) {
        pred[arc.to] = v;
        cost[arc.to] = arc.weight + cost[v];
        queue.emplace(static_cast<double>(cost[arc.to]), arc.to);
      }
    }
  }
  return pred;
}

bool SgRouteFinder::Shortest::dijkstra(const SgPlatform& p, std::size_t zone, std::size_t from, std::size_t to, SgLocalRoute& out) {
  std::vector<SgLocalRoute> hops;  // from the last to the first
  {
    const std::lock_guard<std::mutex> hold(mutex_);
    Graph& g = graph(zone);
    const auto src = g.id_of.find(from);
    const auto dst = g.id_of.find(to);
    if (src == g.id_of.end() || dst == g.id_of.end()) return false;
    if (from == to) {
      const SgEdge* e = finder_.edge(zone, from, to);
      if (e == nullptr) return false;  // the network's loopback
      out = finder_.local_of(p, *e);
      return true;
    }
    const std::vector<std::size_t>& pred = predecessors(g, src->second);
    for (std::size_t v = dst->second; v != src->second; v = pred[v]) {
      const SgEdge* e = finder_.edge(zone, g.vertex_of[pred[v]], g.vertex_of[v]);
      if (e == nullptr || hops.size() >= g.vertex_of.size()) return false;
      hops.push_back(finder_.local_of(p, *e));
    }
  }
  const bool recursive = finder_.recursive(zone);
  for (std::size_t i = 0; i + 1 < hops.size(); ++i) {
    // SimGrid asks for the route joining two gateways that differ with null netpoints, and fails.
    if (recursive && hops[i].gw_src && hops[i + 1].gw_dst && !(*hops[i].gw_src == *hops[i + 1].gw_dst)) return false;
  }
  if (recursive) {
    out.gw_src = hops.back().gw_src;
    out.gw_dst = hops.front().gw_dst;
  }
  for (auto hop = hops.rbegin(); hop != hops.rend(); ++hop) out.links.insert(out.links.end(), hop->links.begin(), hop->links.end());
  return true;
}

}  // namespace pagecache::formats::simgrid
