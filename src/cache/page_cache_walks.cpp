// CacheWalks: the walks and steps of walks a policy takes, on PageCache's lists.

#include "cache/cache_walks.hpp"

#include "cache/page_cache.hpp"
#include "engine/check.hpp"

namespace pagecache::cache {

std::int64_t CacheWalks::evict_clean(ListKind kind, std::int64_t budget, FileId excluded, bool spare_written) {
  return cache_->evict_clean(kind, budget, excluded, spare_written);
}

std::int64_t CacheWalks::deactivate_oldest(std::int64_t budget, FileId excluded, bool spare_written) {
  return cache_->deactivate_oldest(budget, excluded, spare_written);
}

BlockId CacheWalks::oldest_dirty() const noexcept { return cache_->dirty_by_age_.front(); }

BlockId CacheWalks::lru_expired(double cutoff) { return cache_->lru_expired(cutoff); }

void CacheWalks::balance() { cache_->balance(); }

CacheWalks::CleanScan CacheWalks::scan_clean(ListKind kind) const noexcept {
  CleanScan scan;
  scan.cache_ = cache_;
  scan.list_ = &cache_->list(kind);
  scan.at_.fill(kNoBlock);
  if (cache_->nodes_.empty() || cache_->target_node_ != kAnyNode) {
    const NodeId node = cache_->target_node_ == kAnyNode ? 0 : cache_->target_node_;
    scan.at_[node] = scan.list_->front(BlockState::Clean, node);
  } else {
    for (NodeId n = 0; n < cache_->nodes_.size(); ++n) scan.at_[n] = scan.list_->front(BlockState::Clean, n);
  }
  return scan;
}

BlockId CacheWalks::CleanScan::next() noexcept {
  for (;;) {
    // The oldest of the nodes' next blocks.
    std::size_t oldest = kMaxNodes;
    for (std::size_t n = 0; n < kMaxNodes; ++n) {
      if (at_[n] != kNoBlock && (oldest == kMaxNodes || list_->block(at_[n]).order < list_->block(at_[oldest]).order)) oldest = n;
    }
    if (oldest == kMaxNodes) return kNoBlock;
    const BlockId id = at_[oldest];
    at_[oldest] = list_->next_in_state(id);
    if (cache_->in_target(list_->block(id))) return id;
  }
}

void CacheWalks::CleanScan::moved(BlockId block) noexcept {
  const Block& b = list_->block(block);
  PC_ASSERT(b.list == list_->kind() && b.state == BlockState::Clean);
  if (at_[b.node] == kNoBlock) at_[b.node] = block;
}

BlockId CacheWalks::first(ListKind kind) const noexcept {
  const BlockId front = cache_->list(kind).front();
  return front == kNoBlock || cache_->in_target(cache_->blocks_[front]) ? front : next(front);
}

BlockId CacheWalks::next(BlockId block) const noexcept {
  const LruList& list = cache_->list(cache_->blocks_[block].list);
  BlockId id = list.next(block);
  while (id != kNoBlock && !cache_->in_target(cache_->blocks_[id])) id = list.next(id);
  return id;
}

const Block& CacheWalks::block(BlockId block) const noexcept { return cache_->blocks_[block]; }

void CacheWalks::set_bits(BlockId block, std::uint8_t bits) noexcept {
  PC_ASSERT(bits <= kMaxPolicyBits);
  set_policy_bits(cache_->blocks_[block], bits);
}

std::int64_t CacheWalks::evict(BlockId block, std::int64_t bytes) {
  PC_ASSERT(bytes > 0 && cache_->blocks_[block].state == BlockState::Clean && cache_->in_target(cache_->blocks_[block]));
  return cache_->evict_front(block, bytes, cache_->blocks_[block].list);
}

void CacheWalks::move_to_back(BlockId block, ListKind to, bool referenced) { cache_->move_to_back(block, to, referenced); }

}  // namespace pagecache::cache
