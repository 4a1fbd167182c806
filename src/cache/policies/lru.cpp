// The lru policy: one least-recently-used list, no activation. A re-read moves data to the
// most recently used end; reclaim takes the least recently used clean data, any file's.
// Writeback and dirty limits are the kernel's (KernelWriteback). A baseline for what the kernel's two lists
// (and two-touch activation) buy.

#include "cache/policies/kernel_writeback.hpp"

#include <pagecache/cache_policies.hpp>

namespace pagecache::cache {

namespace {

class LruPolicy final : public KernelWriteback {
 public:
  std::string_view name() const noexcept override { return "lru"; }

  // Nothing is ever activated: the inactive list is the one list, the active one stays empty.
  bool read_is_first_touch() const noexcept override { return false; }
  Reread reread(const Block&) const noexcept override { return Reread::Refresh; }
  Balance balance() const noexcept override { return Balance::AfterReads; }

  bool spares_files_being_written() const noexcept override { return false; }
  std::int64_t reclaim(PageCache& cache, std::int64_t amount, FileId excluded) override {
    return cache.walks().evict_clean(ListKind::Inactive, amount, excluded, false);
  }
  std::int64_t evictable(const PageCache& cache) const noexcept override {
    return cache.list(ListKind::Inactive).bytes(BlockState::Clean);
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
