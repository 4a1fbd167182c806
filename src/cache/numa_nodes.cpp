// NumaNodes: the nodes' invariants.

#include "cache/numa_nodes.hpp"

#include "engine/check.hpp"

#include <fmt/format.h>

namespace pagecache::cache {

void NumaNodes::check(const std::int64_t* cached_on, const NodeUse& host) const {
  if (nodes_.empty()) return;
  PC_ASSERT_MSG(toucher_ < nodes_.size(), fmt::format("operations from node {} of {}", toucher_, nodes_.size()));
  NodeUse sum;
  for (NodeId n = 0; n < nodes_.size(); ++n) {
    const NodeUse& use = nodes_[n];
    PC_ASSERT_MSG(use.cached == cached_on[n], fmt::format("node {}: {} bytes cached counted, {} in its blocks", n, use.cached, cached_on[n]));
    PC_ASSERT_MSG(use.free() >= 0 && use.anonymous >= 0 && use.reserved >= 0,
                  fmt::format("node {}: {} total, {} anonymous, {} cached, {} reserved", n, use.total, use.anonymous, use.cached, use.reserved));
    sum.total += use.total, sum.anonymous += use.anonymous, sum.cached += use.cached, sum.reserved += use.reserved;
  }
  PC_ASSERT_MSG(sum.total == host.total && sum.anonymous == host.anonymous && sum.cached == host.cached && sum.reserved == host.reserved,
                "the nodes' memory does not add up to the host's");
}

}  // namespace pagecache::cache
