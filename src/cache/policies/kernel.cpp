// The kernel policy: the decisions of Linux's page cache (mm/swap.c, mm/vmscan.c,
// mm/page-writeback.c, fs/fs-writeback.c). Its parameters are switches: each one off gives
// WRENCH-cache's behaviour for that decision instead (the linux profile's ablations; all off
// is the wrench_cache preset).

#include "cache/page_cache.hpp"
#include "cache/policy.hpp"

#include <pagecache/cache_policies.hpp>

#include <iterator>
#include <string>

namespace pagecache::cache {

namespace {

// The switches, read once from the settings when the policy is made.
struct Switches {
  bool background_writeback;
  bool dirty_throttling;
  bool expire_oldest_first;
  bool two_touch_activation;
  bool protect_files_being_written;
  bool dirtyable_memory;
  bool reclaim_inactive_only;
  bool reclaim_may_take_file_being_read;
  bool flush_splits_in_place;
  bool balance_after_every_change;
};

// In the order `pcsim show` writes them; each with its field of Switches.
constexpr PolicyParameter kParameters[] = {
    {"background_writeback", true, false,
     "above dirty_background_ratio of dirtyable memory the flusher writes the oldest dirty data at once, beside the writers "
     "(mm/page-writeback.c, wb_over_bg_thresh); off: dirty data waits for expiry or a writer at dirty_ratio"},
    {"dirty_throttling", true, false,
     "a writer at the kernel's setpoint is paused until writeback frees quota (balance_dirty_pages), never flushing itself; "
     "needs background_writeback; off: a writer at dirty_ratio flushes a chunk's worth itself"},
    {"expire_oldest_first", true, false,
     "the periodic flusher writes expired data oldest first, as kupdate-style writeback takes inodes by dirtied_when; off: "
     "expired blocks of the inactive list, then the active one, in LRU order (the paper's Algorithm 1)"},
    {"two_touch_activation", true, false,
     "a device read marks data referenced and a re-read activates only referenced data (mark_page_accessed); off: any "
     "re-read activates"},
    {"protect_files_being_written", true, false,
     "reclaim takes the clean data of files open for writing last (the paper observed the kernel keep them)"},
    {"dirtyable_memory", true, false,
     "dirty thresholds are fractions of free + cached memory (global_dirtyable_memory); off: free + cached - dirty"},
    {"reclaim_inactive_only", true, false,
     "reclaim takes clean inactive data and deactivates the oldest active data when none is left (shrink_active_list); off: "
     "clean active data is evicted in place and every inactive byte counts as evictable"},
    {"reclaim_may_take_file_being_read", true, false,
     "making room for a read may evict and flush the file being read; off: it is excluded (the paper's Algorithm 2)"},
    {"flush_splits_in_place", true, false,
     "a partly flushed block is split in place; off: its flushed part moves to the most recently used end of the inactive "
     "list"},
    {"balance_after_every_change", true, false, "the lists are balanced (active <= 2 x inactive) after every change; off: after reads"},
};
constexpr bool Switches::*kFields[] = {
    &Switches::background_writeback,     &Switches::dirty_throttling,   &Switches::expire_oldest_first,
    &Switches::two_touch_activation,     &Switches::protect_files_being_written, &Switches::dirtyable_memory,
    &Switches::reclaim_inactive_only,    &Switches::reclaim_may_take_file_being_read, &Switches::flush_splits_in_place,
    &Switches::balance_after_every_change,
};
static_assert(std::size(kParameters) == std::size(kFields), "a field of Switches for each parameter");

Switches read_switches(const CacheSettings& settings) {
  Switches s{};
  for (std::size_t i = 0; i < std::size(kParameters); ++i) s.*kFields[i] = settings.get(kParameters[i].key);
  return s;
}

class KernelPolicy final : public Policy {
 public:
  explicit KernelPolicy(const CacheSettings& s) : name_(s.policy), s_(read_switches(s)) {}

  // The settings' name: the wrench_cache preset is this policy with every switch off.
  std::string_view name() const noexcept override { return name_; }

  // mark_page_accessed: a read from the device references the page; the next read activates it.
  bool read_is_first_touch() const noexcept override { return s_.two_touch_activation; }
  Reread reread(const Block& block) const noexcept override {
    return s_.two_touch_activation && !block.referenced ? Reread::Mark : Reread::Activate;
  }
  Balance balance() const noexcept override { return s_.balance_after_every_change ? Balance::AfterEveryChange : Balance::AfterReads; }

  bool spares_files_being_written() const noexcept override { return s_.protect_files_being_written; }
  std::int64_t reclaim(PageCache& cache, std::int64_t amount, FileId excluded) override {
    // shrink_inactive_list takes clean inactive data; with none left, shrink_active_list ages
    // the active list. Files being written are spared in a first pass when asked.
    std::int64_t evicted = 0;
    auto pass = [&](bool spare_written) {
      evicted += cache.walks().evict_clean(ListKind::Inactive, amount - evicted, excluded, spare_written);
      if (s_.reclaim_inactive_only) evicted += cache.walks().deactivate_oldest(amount - evicted, excluded, spare_written);
      else evicted += cache.walks().evict_clean(ListKind::Active, amount - evicted, excluded, spare_written);
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
    return s_.expire_oldest_first ? cache.walks().oldest_dirty() : cache.walks().lru_expired(cutoff);
  }
  bool splits_flushed_block_in_place() const noexcept override { return s_.flush_splits_in_place; }
  bool background_writeback() const noexcept override { return s_.background_writeback; }
  // Throttled writers wait for the flusher's background writeback; without it, they flush.
  bool throttles_writers() const noexcept override { return s_.dirty_throttling && s_.background_writeback; }

  // global_dirtyable_memory: free + file pages; copies into the cache in flight (reserved)
  // are file pages already, as the kernel dirties pages one by one while the copy runs.
  std::int64_t dirtyable(const PageCache& cache) const noexcept override {
    const MemoryState m = cache.memory();
    return s_.dirtyable_memory ? m.free + m.cached + m.reserved : m.free + m.cached - m.dirty - m.writeback;
  }

 private:
  std::string name_;
  Switches s_;
};

}  // namespace

extern const PolicyRegistration kKernelPolicy{
    .declaration = {
        .name = "kernel",
        .doc = "the kernel's decisions (mm/swap.c, mm/vmscan.c, mm/page-writeback.c, fs/fs-writeback.c), each a switch",
        .parameters = kParameters,
        .preset_of = {},
    },
    .make = [](const CacheSettings& settings) -> std::unique_ptr<Policy> { return std::make_unique<KernelPolicy>(settings); },
};

}  // namespace pagecache::cache
