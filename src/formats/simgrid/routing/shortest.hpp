#pragma once
// The routes of Floyd and Dijkstra zones: the fewest links over the zone's declared routes,
// each route an edge weighing its number of links, with SimGrid's tie rules. Floyd relaxes
// through vertices in order of declaration and keeps the first of equal paths; Dijkstra takes
// vertices by (cost, order of first appearance in a route) and keeps the first predecessor
// that improves. A vertex with no declared route to itself gets SimGrid's network loopback
// (pcsim: no route, the loopback being the model's) unless the zone has sub-zones.

#include "formats/simgrid/routing/routing.hpp"

#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <vector>

namespace pagecache::formats::simgrid {

struct SgRouteFinder::Shortest {
  explicit Shortest(const SgRouteFinder& finder) : finder_(finder), floyd_(finder.zone_count()), dijkstra_(finder.zone_count()) {}

  /// Floyd's route between two vertices of `zone`: its tables built on first use when the zone
  /// has at most kFloydMost vertices, else Dijkstra's route (the same but maybe for ties).
  bool floyd(const SgPlatform& p, std::size_t zone, std::size_t from, std::size_t to, SgLocalRoute& out, int depth);
  /// Dijkstra's route between two vertices of `zone`, its predecessors kept per source.
  bool dijkstra(const SgPlatform& p, std::size_t zone, std::size_t from, std::size_t to, SgLocalRoute& out);

  static constexpr std::size_t kFloydMost = 400;  // 6.4 * 10^7 relaxations, about 0.1 s

 private:
  struct FloydTables {
    std::size_t n = 0;
    std::vector<std::uint64_t> cost;  // n * n
    std::vector<long> pred;           // n * n, -1 for none
    std::vector<bool> loopback;       // per vertex: its route to itself is the network's loopback
  };
  struct Graph {
    bool built = false;
    std::vector<std::size_t> vertex_of;                              // graph id -> vertex
    std::map<std::size_t, std::size_t> id_of;                        // vertex -> graph id
    struct Arc {
      std::size_t to;
      std::uint64_t weight;  // the route's links (the loopback's: 1)
      bool loopback;
    };
    std::vector<std::vector<Arc>> out;                               // per graph id
    std::map<std::size_t, std::vector<std::size_t>> pred_from;       // per source graph id
  };

  const FloydTables& floyd_tables(std::size_t zone);
  Graph& graph(std::size_t zone);
  const std::vector<std::size_t>& predecessors(Graph& g, std::size_t src);

  const SgRouteFinder& finder_;
  std::mutex mutex_;  // over the tables, built on first use
  std::vector<std::unique_ptr<FloydTables>> floyd_;
  std::vector<Graph> dijkstra_;
};

}  // namespace pagecache::formats::simgrid
