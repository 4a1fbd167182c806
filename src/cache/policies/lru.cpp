// The lru policy: one least-recently-used list, no activation. A re-read moves data to the
// most recently used end; reclaim takes the least recently used clean data, any file's.
// Writeback and dirty limits are the kernel's. A baseline for what the kernel's two lists
// (and two-touch activation) buy.

#include "cache/page_cache.hpp"
#include "cache/policy.hpp"

#include <pagecache/cache_policies.hpp>

namespace pagecache::cache {

namespace {

class LruPolicy final : public Policy {
 public:
  std::string_view name() const noexcept override { return "lru"; }

  // Nothing is ever activated: the inactive list is the one list, the active one stays empty.
  bool read_is_first_touch() const noexcept override { return false; }
  Reread reread(const Block&) const noexcept override { return Reread::Refresh; }
  bool balances_after_every_change() const noexcept override { return false; }

  bool spares_files_being_written() const noexcept override { return false; }
  std::int64_t reclaim(PageCache& cache, std::int64_t amount, FileId excluded) override {
    return cache.walks().evict_clean(ListKind::Inactive, amount, excluded, false);
  }
  std::int64_t evictable(const PageCache& cache) const noexcept override {
    return cache.list(ListKind::Inactive).bytes(BlockState::Clean);
  }
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

}  // namespace

extern const PolicyRegistration kLruPolicy{
    .declaration = {
        .name = "lru",
        .doc = "one least-recently-used list, no activation, the kernel's writeback: a baseline",
        .parameters = {},
        .preset_of = {},
    },
    .make = [](const CacheSettings&) -> std::unique_ptr<Policy> { return std::make_unique<LruPolicy>(); },
};

}  // namespace pagecache::cache
