#pragma once
// KernelWriteback: the kernel's writeback and dirty limits, for a policy that changes only which
// data stays cached (lru, clock, arc): expired data written oldest first (kupdate-style
// writeback takes inodes by dirtied_when), a partly flushed block split in place, background
// writeback above dirty_background_ratio, writers at the setpoint paced (balance_dirty_pages),
// and the thresholds fractions of free + cached memory (global_dirtyable_memory; copies in
// flight are file pages already). Reclaim may take the file being read, as the kernel's knows
// no file.

#include "cache/page_cache.hpp"
#include "cache/policy.hpp"

namespace pagecache::cache {

class KernelWriteback : public Policy {
 public:
  bool reclaim_may_take_file_being_read() const noexcept override { return true; }
  BlockId next_expired(PageCache& cache, double) const override { return cache.walks().oldest_dirty(); }
  bool splits_flushed_block_in_place() const noexcept override { return true; }
  bool background_writeback() const noexcept override { return true; }
  bool throttles_writers() const noexcept override { return true; }
  std::int64_t dirtyable(const PageCache& cache) const noexcept override {
    const MemoryState memory = cache.memory();
    return memory.free + memory.cached + memory.reserved;
  }
};

}  // namespace pagecache::cache
