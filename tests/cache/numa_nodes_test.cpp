// NumaNodes on its own: the split, placement from the toucher's node, release, and its check.
#include "cache/numa_nodes.hpp"

#include <pagecache/error.hpp>

#include <catch2/catch.hpp>

#include <cstdint>
#include <utility>
#include <vector>

using namespace pagecache;
using namespace pagecache::cache;

TEST_CASE("new memory goes to the toucher's node first, then the next", "[numa]") {
  NumaNodes nodes;
  CHECK(nodes.count() == 1);  // an empty table: one node, nothing kept
  nodes.split(1001, 2);
  CHECK(nodes.count() == 2);
  CHECK(nodes[0].total == 501);
  CHECK(nodes[1].total == 500);
  nodes.touch_from(1);
  std::vector<std::pair<NodeId, std::int64_t>> parts;
  auto take = [&](NodeId node, std::int64_t bytes) {
    parts.emplace_back(node, bytes);
    nodes[node].anonymous += bytes;
  };
  nodes.place(300, nodes.toucher(), take);
  nodes.place(400, nodes.toucher(), take);  // 200 left on node 1: the rest on node 0
  CHECK(parts == std::vector<std::pair<NodeId, std::int64_t>>{{1, 300}, {1, 200}, {0, 200}});
  // Given back from the toucher's node first.
  std::int64_t given = 0;
  nodes.release(550, nodes.toucher(), &NodeUse::anonymous, [&](NodeId, std::int64_t bytes) { given += bytes; });
  CHECK(given == 550);
  CHECK(nodes[1].anonymous == 0);
  CHECK(nodes[0].anonymous == 150);
}

TEST_CASE("NumaNodes' check: the nodes add up to the host, none holds more than it has", "[numa]") {
  NumaNodes nodes;
  nodes.split(1000, 2);
  nodes[0].cached = 100;
  nodes[1].anonymous = 200;
  const std::int64_t cached_on[] = {100, 0};
  CHECK_NOTHROW(nodes.check(cached_on, NodeUse{.total = 1000, .anonymous = 200, .cached = 100}));
  const std::int64_t other_blocks[] = {90, 10};
  CHECK_THROWS_AS(nodes.check(other_blocks, NodeUse{.total = 1000, .anonymous = 200, .cached = 100}), InvariantError);
  CHECK_THROWS_AS(nodes.check(cached_on, NodeUse{.total = 1000, .anonymous = 250, .cached = 100}), InvariantError);
  nodes[1].anonymous = 600;  // more than the node's 500
  CHECK_THROWS_AS(nodes.check(cached_on, NodeUse{.total = 1000, .anonymous = 600, .cached = 100}), InvariantError);
  nodes[1].anonymous = 200;
  nodes.touch_from(2);  // no such node
  CHECK_THROWS_AS(nodes.check(cached_on, NodeUse{.total = 1000, .anonymous = 200, .cached = 100}), InvariantError);
}
