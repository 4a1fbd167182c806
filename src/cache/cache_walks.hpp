#pragma once
// CacheWalks: what a policy may do to the page cache's lists (Policy::reclaim,
// Policy::next_expired). Whole walks the kernel's reclaim takes (evict_clean,
// deactivate_oldest, balance), and the steps a policy's own walk is made of (scan_clean or
// first/next, evict, move_to_back, set_bits), so that a policy with a walk of its own, such as CLOCK's second chance, is
// written in its own file. The walks change the lists and leave settling to the operation that
// called the policy; each block they evict is reported to the policy (Policy::evicted). They
// take only the target's data (a memory group's, a NUMA node's) when PageCache::evict has one.

#include "cache/block.hpp"
#include "cache/lru_list.hpp"
#include "cache/numa_nodes.hpp"

#include <array>
#include <cstdint>

namespace pagecache::cache {

class PageCache;

class CacheWalks {
 public:
  explicit CacheWalks(PageCache& cache) noexcept : cache_(&cache) {}

  // --- Whole walks ------------------------------------------------------------------------
  /// Evicts clean blocks of `kind`, least recently used first, up to `budget` bytes (the last
  /// one split), skipping `excluded` and, if `spare_written` (the policy spares files being
  /// written), the files being written. Returns the bytes evicted.
  std::int64_t evict_clean(ListKind kind, std::int64_t budget, FileId excluded, bool spare_written);
  /// Active list aging (mm/vmscan.c, shrink_active_list): moves the oldest active data to the
  /// inactive list, evicting it if clean and not spared as evict_clean spares, until `budget`
  /// bytes are evicted or the active list is empty. Returns the bytes evicted.
  std::int64_t deactivate_oldest(std::int64_t budget, FileId excluded, bool spare_written);
  /// The dirty block that became dirty first, or kNoBlock.
  BlockId oldest_dirty() const noexcept;
  /// The least recently used dirty block with entry time <= `cutoff`, inactive list first,
  /// or kNoBlock. Repeated searches under one cutoff resume where the last one stopped.
  BlockId lru_expired(double cutoff);
  /// Moves least recently used active data to the inactive list until active <= 2 x inactive.
  void balance();

  // --- Steps of a policy's own walk -------------------------------------------------------
  /// The target's clean blocks of one list, least recently used first (a host's nodes' blocks
  /// merged by their order in the list, unless one node is the target).
  class CleanScan {
   public:
    /// The next block, or kNoBlock at the end. Read it before evicting or moving the current.
    BlockId next() noexcept;
    /// `block`, of the list scanned, was just moved to its back: it is met again at the end.
    void moved(BlockId block) noexcept;

   private:
    friend class CacheWalks;
    const PageCache* cache_ = nullptr;
    const LruList* list_ = nullptr;
    std::array<BlockId, kMaxNodes> at_{};  // by node: the next clean block of its sub-list
  };
  CleanScan scan_clean(ListKind kind) const noexcept;
  /// The target's first block of `kind` in LRU order, whatever its state, and the target's
  /// next after `block` (read it before moving or evicting `block`); kNoBlock at the end.
  BlockId first(ListKind kind) const noexcept;
  BlockId next(BlockId block) const noexcept;
  const Block& block(BlockId block) const noexcept;
  /// Sets the policy's bits of `block` (at most kMaxPolicyBits); nothing moves.
  void set_bits(BlockId block, std::uint8_t bits) noexcept;
  /// Evicts the first `bytes` (> 0) of clean `block`, up to a page boundary of a file held by
  /// range, or all of it if it is smaller; returns the bytes evicted.
  std::int64_t evict(BlockId block, std::int64_t bytes);
  /// Moves `block` to the most recently used end of `to`, its referenced mark set as given
  /// (its policy bits kept).
  void move_to_back(BlockId block, ListKind to, bool referenced);

 private:
  PageCache* cache_;
};

}  // namespace pagecache::cache
