// The clock policy: CLOCK, or second chance (F. J. Corbató, "A Paging Experiment with the
// Multics System", MIT Project MAC, MAC-M-384, 1968; A. S. Tanenbaum and H. Bos, Modern
// Operating Systems, 4th ed., §3.4.4-3.4.5). The data sits in one list in the order it
// arrived, each block with a reference bit; the list's front is the clock's hand. A read from
// the device sets the bit (that access references the data), a re-read only sets it again:
// nothing moves on a hit. Reclaim moves the hand over clean data: referenced data has its bit
// cleared and goes behind the hand (to the back), the first unreferenced data is evicted.
// Dirty data and data in writeback are passed over, bits kept: the flusher writes them.
// Writeback and dirty limits are the kernel's (KernelWriteback), as lru's. FIFO with one bit of recency: a
// baseline between lru and the kernel's two lists.

#include "cache/policies/kernel_writeback.hpp"

#include <pagecache/cache_policies.hpp>

namespace pagecache::cache {

namespace {

class ClockPolicy final : public KernelWriteback {
 public:
  std::string_view name() const noexcept override { return "clock"; }

  // Nothing is ever activated: the inactive list is the clock, the active one stays empty.
  bool read_is_first_touch() const noexcept override { return true; }
  Reread reread(const Block&) const noexcept override { return Reread::Mark; }
  Balance balance() const noexcept override { return Balance::AfterReads; }

  bool spares_files_being_written() const noexcept override { return false; }
  std::int64_t reclaim(PageCache& cache, std::int64_t amount, FileId excluded) override {
    CacheWalks walks = cache.walks();
    CacheWalks::CleanScan hand = walks.scan_clean(ListKind::Inactive);
    std::int64_t evicted = 0;
    // Each block is met at most twice: a second time only with its bit cleared.
    for (BlockId id = hand.next(); id != kNoBlock && evicted < amount;) {
      const BlockId next = hand.next();  // read before `id` moves or goes
      if (const Block& block = walks.block(id); block.file != excluded && block.referenced) {
        walks.move_to_back(id, ListKind::Inactive, false);
        hand.moved(id);
      } else if (block.file != excluded) {
        evicted += walks.evict(id, amount - evicted);
      }
      id = next != kNoBlock ? next : hand.next();
    }
    return evicted;
  }
  std::int64_t evictable(const PageCache& cache) const noexcept override {
    return cache.list(ListKind::Inactive).bytes(BlockState::Clean);
  }
};

}  // namespace

extern const PolicyRegistration kClockPolicy{
    .declaration = {
        .name = "clock",
        .doc = "CLOCK (second chance): one list in arrival order, a re-read sets a reference bit, reclaim passes over referenced "
               "data once; the kernel's writeback",
        .parameters = {},
        .preset_of = {},
    },
    .make = [](const CacheSettings&) -> std::unique_ptr<Policy> { return std::make_unique<ClockPolicy>(); },
};

}  // namespace pagecache::cache
