// PageCache: NUMA nodes (docs/model.md §6.20): the memory's split, reclaim node by node, and
// the nodes' invariants. Placement itself is NumaNodes::place, called where memory is taken.

#include "cache/page_cache.hpp"

#include "engine/check.hpp"

#include <fmt/format.h>

#include <array>

namespace pagecache::cache {

void PageCache::set_nodes(int count) {
  if (count < 1 || count > kMaxNodes) throw ConfigError(fmt::format("a host has 1 to {} NUMA nodes, got {}", kMaxNodes, count));
  PC_ASSERT_MSG(anonymous_ == 0 && cached() == 0 && reserved_ == 0, "NUMA nodes are set before any memory is held");
  if (count > 1) nodes_.split(total_, count);
}

NodeUse PageCache::node(NodeId node) const noexcept {
  if (nodes_.empty()) return NodeUse{.total = total_, .anonymous = anonymous_, .cached = cached(), .reserved = reserved_};
  return nodes_[node];
}

std::int64_t PageCache::evict_by_node(std::int64_t amount, FileId excluded) {
  // Every node's kswapd is woken when no node can take an allocation (wake_all_kswapds), and
  // each balances its own node from its own lists (mm/vmscan.c, balance_pgdat since 4.8).
  const auto count = static_cast<std::int64_t>(nodes_.size());
  const std::int64_t share = (amount + count - 1) / count;
  std::int64_t evicted = 0;
  for (NodeId node = 0; node < nodes_.size() && evicted < amount; ++node) {
    target_node_ = node;
    evicted += policy_->reclaim(*this, std::min(share, amount - evicted), excluded);
  }
  for (NodeId node = 0; node < nodes_.size() && evicted < amount; ++node) {
    target_node_ = node;
    evicted += policy_->reclaim(*this, amount - evicted, excluded);
  }
  target_node_ = kAnyNode;
  return evicted;
}

void PageCache::check_nodes() const {
  if (nodes_.empty()) return;
  std::array<std::int64_t, kMaxNodes> cached_on{};
  for (const LruList* list : {&inactive_, &active_}) {
    for (BlockId id = list->front(); id != kNoBlock; id = list->next(id)) {
      const Block& block = blocks_[id];
      PC_ASSERT_MSG(block.node < nodes_.size(), fmt::format("block {} on node {} of {}", id, block.node, nodes_.size()));
      cached_on[block.node] += block.size;
    }
  }
  NodeUse sum;
  for (NodeId n = 0; n < nodes_.size(); ++n) {
    const NodeUse& use = nodes_[n];
    PC_ASSERT_MSG(use.cached == cached_on[n], fmt::format("node {}: {} bytes cached counted, {} in its blocks", n, use.cached, cached_on[n]));
    PC_ASSERT_MSG(use.free() >= 0 && use.anonymous >= 0 && use.reserved >= 0,
                  fmt::format("node {}: {} total, {} anonymous, {} cached, {} reserved", n, use.total, use.anonymous, use.cached, use.reserved));
    sum.total += use.total, sum.anonymous += use.anonymous, sum.cached += use.cached, sum.reserved += use.reserved;
  }
  PC_ASSERT_MSG(sum.total == total_ && sum.anonymous == anonymous_ && sum.cached == cached() && sum.reserved == reserved_,
                "the nodes' memory does not add up to the host's");
}

}  // namespace pagecache::cache
