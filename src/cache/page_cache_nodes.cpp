// PageCache: NUMA nodes (docs/model.md §6.20): reclaim node by node, and the blocks' nodes
// against the nodes' counts. Placement itself is NumaNodes::place, called where memory is taken.

#include "cache/page_cache.hpp"

#include "engine/check.hpp"

#include <fmt/format.h>

#include <array>

namespace pagecache::cache {

NodeUse node_use(const PageCache& cache, NodeId node) noexcept {
  if (!cache.nodes().empty()) return cache.nodes()[node];
  const MemoryState memory = cache.memory();
  return NodeUse{.total = memory.total, .anonymous = memory.anonymous, .cached = memory.cached, .reserved = memory.reserved};
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
  nodes_.check(cached_on.data(), NodeUse{.total = total_, .anonymous = anonymous_, .cached = cached(), .reserved = reserved_});
}

}  // namespace pagecache::cache
