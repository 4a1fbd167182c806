// The kernel policy: the decisions of Linux's page cache (mm/swap.c, mm/vmscan.c,
// mm/page-writeback.c, fs/fs-writeback.c). CacheSettings' switches are its parameters: each
// one off gives WRENCH-cache's behaviour for that decision instead (the linux profile's
// ablations; with all off, the wrench_cache policy's decisions).

#include "cache/page_cache.hpp"
#include "cache/policy.hpp"

namespace pagecache::cache {

namespace {

class KernelPolicy final : public Policy {
 public:
  explicit KernelPolicy(const CacheSettings& s) : s_(s) {}

  std::string_view name() const noexcept override { return "kernel"; }

  // mark_page_accessed: a read from the device references the page; the next read activates it.
  bool read_is_first_touch() const noexcept override { return s_.two_touch_activation; }
  Reread reread(const Block& block) const noexcept override {
    return s_.two_touch_activation && !block.referenced ? Reread::Mark : Reread::Activate;
  }
  bool balances_after_every_change() const noexcept override { return s_.balance_after_every_change; }

  bool spares_files_being_written() const noexcept override { return s_.protect_files_being_written; }
  std::int64_t reclaim(PageCache& cache, std::int64_t amount, FileId excluded) const override {
    // shrink_inactive_list takes clean inactive data; with none left, shrink_active_list ages
    // the active list. Files being written are spared in a first pass when asked.
    std::int64_t evicted = 0;
    auto pass = [&](bool spare_written) {
      evicted += cache.evict_clean(ListKind::Inactive, amount - evicted, excluded, spare_written);
      if (s_.reclaim_inactive_only) evicted += cache.deactivate_oldest(amount - evicted, excluded, spare_written);
      else evicted += cache.evict_clean(ListKind::Active, amount - evicted, excluded, spare_written);
    };
    pass(s_.protect_files_being_written);
    if (evicted < amount && s_.protect_files_being_written) pass(false);
    return evicted;
  }
  std::int64_t evictable(const PageCache& cache) const noexcept override {
    const LruList& inactive = cache.list(ListKind::Inactive);
    return s_.reclaim_inactive_only ? inactive.bytes(BlockState::Clean) : inactive.bytes();
  }
  bool reclaim_may_take_file_being_read() const noexcept override { return s_.reclaim_may_take_file_being_read; }

  // kupdate-style writeback takes expired inodes in the order they were dirtied.
  BlockId next_expired(PageCache& cache, double cutoff) const override {
    return s_.expire_oldest_first ? cache.oldest_dirty() : cache.lru_expired(cutoff);
  }
  bool splits_flushed_block_in_place() const noexcept override { return s_.flush_splits_in_place; }
  bool background_writeback() const noexcept override { return s_.background_writeback; }
  // Throttled writers wait for the flusher's background writeback; without it, they flush.
  bool throttles_writers() const noexcept override { return s_.dirty_throttling && s_.background_writeback; }

  // The copy is a memcpy by the application's thread (copy_page_to_iter, copy_page_from_iter).
  bool copies_hold_cores() const noexcept override { return s_.copies_hold_cores; }
  bool large_folios() const noexcept override { return s_.large_folios; }

  // global_dirtyable_memory: free + file pages; copies into the cache in flight (reserved)
  // are file pages already, as the kernel dirties pages one by one while the copy runs.
  std::int64_t dirtyable(const PageCache& cache) const noexcept override {
    return s_.dirtyable_memory ? cache.free() + cache.cached() + cache.reserved()
                               : cache.free() + cache.cached() - cache.dirty() - cache.writeback();
  }

 private:
  CacheSettings s_;
};

}  // namespace

std::unique_ptr<Policy> make_kernel_policy(const CacheSettings& settings) { return std::make_unique<KernelPolicy>(settings); }

}  // namespace pagecache::cache
