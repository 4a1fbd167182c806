// The wrench_cache policy: the paper's model as WRENCH-cache implements it
// (docs/wrench-cache.md), where the paper leaves a decision open. Fixed: it has
// no parameters beyond the kernel knobs every policy reads (ratios, expiry, interval).

#include "cache/page_cache.hpp"
#include "cache/policy.hpp"

namespace pagecache::cache {

namespace {

class WrenchCachePolicy final : public Policy {
 public:
  std::string_view name() const noexcept override { return "wrench_cache"; }

  // Any re-read activates (the paper's Algorithm 2); the lists are balanced after reads only.
  bool read_is_first_touch() const noexcept override { return false; }
  Reread reread(const Block&) const noexcept override { return Reread::Activate; }
  bool balances_after_every_change() const noexcept override { return false; }

  // Clean data, least recently used first: the inactive list, then the active list in place.
  bool spares_files_being_written() const noexcept override { return false; }
  std::int64_t reclaim(PageCache& cache, std::int64_t amount, FileId excluded) const override {
    std::int64_t evicted = cache.evict_clean(ListKind::Inactive, amount, excluded, false);
    evicted += cache.evict_clean(ListKind::Active, amount - evicted, excluded, false);
    return evicted;
  }
  // Every inactive byte counts as evictable, dirty included.
  std::int64_t evictable(const PageCache& cache) const noexcept override { return cache.list(ListKind::Inactive).bytes(); }
  // Algorithm 2 excludes the file being read from what making room may take.
  bool reclaim_may_take_file_being_read() const noexcept override { return false; }

  // Algorithm 1: expired blocks of the inactive list, then of the active list, in LRU order.
  BlockId next_expired(PageCache& cache, double cutoff) const override { return cache.lru_expired(cutoff); }
  // The flushed part of a split block moves to the MRU end of the inactive list.
  bool splits_flushed_block_in_place() const noexcept override { return false; }
  // Dirty data waits for expiry or for a writer at dirty_ratio, who flushes it.
  bool background_writeback() const noexcept override { return false; }
  bool throttles_writers() const noexcept override { return false; }

  // free + cached - dirty, dirty including writeback.
  std::int64_t dirtyable(const PageCache& cache) const noexcept override {
    return cache.free() + cache.cached() - cache.dirty() - cache.writeback();
  }
};

}  // namespace

std::unique_ptr<Policy> make_wrench_cache_policy(const CacheSettings&) { return std::make_unique<WrenchCachePolicy>(); }

}  // namespace pagecache::cache
