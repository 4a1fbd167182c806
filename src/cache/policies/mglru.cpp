// The mglru policy: the kernel's multi-generation LRU (CONFIG_LRU_GEN; mm/vmscan.c,
// mm/workingset.c, mm/swap.c and include/linux/mm_inline.h of v6.14 and later) for page cache
// reached by read() and write(), each rule with its source in docs/model.md §6 (`mglru`).
//
// Without page tables, new data only ever lands in the oldest generation or the next one, so
// the two lists hold them: the inactive list is the oldest generation (its front the tail
// eviction takes from), the active list the next; the younger generations stay empty. Reads
// only count references in the block's bits (refs 1-4, then the working set); nothing moves
// on a hit. Reclaim takes the oldest generation from its tail: data of a tier the refault
// feedback protects (or with every reference counted and the working-set mark) and dirty data
// go to the next generation, the dirty marked for reclaim, and clean data is evicted, leaving a
// shadow. When the oldest generation is empty it is retired: the next becomes the oldest, and
// the tier counters are folded into their averages. Data refaulting while its generation is
// still the oldest counts for its tier, and working-set data comes back one generation younger.
// Data whose writeback ends with the reclaim mark goes to the oldest generation's tail.
// Writeback and dirty limits are the kernel's (KernelWriteback).

#include "cache/policies/kernel_writeback.hpp"

#include <pagecache/cache_policies.hpp>

#include <algorithm>
#include <array>
#include <deque>
#include <iterator>
#include <map>
#include <unordered_map>

namespace pagecache::cache {

namespace {

// Block::policy_bits: the references by read (0-4: PG_referenced, then the 2-bit counter),
// PG_workingset and PG_reclaim.
constexpr std::uint8_t kRefs = 0x7;
constexpr std::uint8_t kWorkingset = 0x8;
constexpr std::uint8_t kReclaim = 0x10;
constexpr int kMaxRefs = 4;
constexpr int kTiers = 4;  // MAX_NR_TIERS

constexpr PolicyParameter kParameters[] = {
    {"refault_batch", std::int64_t{64}, std::int64_t{64},
     "pages a tier must have refaulted before its refault ratio may protect the tiers above it (MIN_LRU_BATCH, "
     "BITS_PER_LONG: 64 on 64-bit machines, 32 on 32-bit ones)",
     ParameterKind::Integer, 1, 4096},
};

constexpr int refs(std::uint8_t bits) noexcept { return bits & kRefs; }
constexpr bool workingset(std::uint8_t bits) noexcept { return (bits & kWorkingset) != 0; }
// lru_tier_from_refs: the working set is tier 3, other data order_base_2(refs).
constexpr int tier(int refs, bool workingset) noexcept { return workingset ? 3 : refs <= 1 ? 0 : refs == 2 ? 1 : 2; }
constexpr int tier(std::uint8_t bits) noexcept { return tier(refs(bits), workingset(bits)); }

// What eviction leaves of data (workingset.c, lru_gen_eviction): its refs less one, as the
// shadow's token keeps them, and its working-set mark.
struct Shadow {
  std::int64_t bytes = 0;
  std::uint8_t refs = 0;
  bool workingset = false;
};
struct RangedShadow {
  std::int64_t end = 0;
  std::uint8_t refs = 0;
  bool workingset = false;
};
struct FileShadows {
  std::deque<Shadow> whole;                     // a file held whole: in eviction order, oldest first
  std::map<std::int64_t, RangedShadow> ranged;  // by offset, disjoint
};

// A tier's feedback (vmscan.c, read_ctrl_pos): refaults against what left the oldest generation.
struct Ctrl {
  std::int64_t refaulted = 0;
  std::int64_t total = 0;
  std::int64_t gain = 0;
};

// positive_ctrl_err: the process variable's refault ratio is not above the set point's (scaled
// by the gains), or it has fewer than `batch` refaults to tell.
__extension__ using Wide = __int128;  // page counts times page counts times a gain
bool at_or_below(const Ctrl& sp, const Ctrl& pv, std::int64_t batch) noexcept {
  if (pv.refaulted < batch) return true;
  return static_cast<Wide>(pv.refaulted) * (sp.total + batch) * sp.gain <= static_cast<Wide>(sp.refaulted + 1) * pv.total * pv.gain;
}

class MglruPolicy final : public KernelWriteback {
 public:
  explicit MglruPolicy(const CacheSettings& settings) : batch_(settings.integer("refault_batch")) {}

  std::string_view name() const noexcept override { return "mglru"; }

  // mm/swap.c, folio_mark_accessed -> lru_gen_inc_refs: a read counts, nothing moves.
  bool read_is_first_touch() const noexcept override { return false; }
  Reread reread(const Block&) const noexcept override { return Reread::Mark; }
  bool rereads_in_place() const noexcept override { return true; }
  std::uint8_t reread_bits(const Block& block) const noexcept override {
    const std::uint8_t bits = block.policy_bits;
    if (refs(bits) < kMaxRefs) return static_cast<std::uint8_t>(bits + 1);
    return bits | kWorkingset;
  }
  Balance balance() const noexcept override { return Balance::Never; }

  // filemap_add_folio -> lru_gen_refault, then lru_gen_add_folio (lru_gen_folio_seq, rule 4).
  bool places_arrivals() const noexcept override { return true; }
  Arrival arriving(const PageCache& cache, FileId file, std::int64_t offset, std::int64_t bytes, bool demand) override {
    const Placement cold{.list = ListKind::Inactive, .referenced = false, .bits = demand ? std::uint8_t{1} : std::uint8_t{0}};
    const auto found = shadows_.find(file);
    if (found == shadows_.end()) return {bytes, cold};
    FileShadows& shadows = found->second;
    Shadow hit;
    if (offset == kNoOffset) {
      if (shadows.whole.empty()) return {bytes, cold};
      Shadow& oldest = shadows.whole.front();
      hit = {std::min(bytes, oldest.bytes), oldest.refs, oldest.workingset};
      if ((oldest.bytes -= hit.bytes) == 0) shadows.whole.pop_front();
    } else {
      auto at = shadows.ranged.upper_bound(offset);
      if (at != shadows.ranged.begin() && std::prev(at)->second.end > offset) {
        --at;
      } else {
        // No shadow at `offset`: cold up to the next one.
        const std::int64_t cold_bytes = at == shadows.ranged.end() ? bytes : std::min(bytes, at->first - offset);
        return {cold_bytes, cold};
      }
      const RangedShadow shadow = at->second;
      hit = {std::min(offset + bytes, shadow.end) - offset, shadow.refs, shadow.workingset};
      forget(shadows.ranged, offset, offset + hit.bytes);
    }
    // A recent refault (lru_gen_test_recent: shadows live one generation, see retire) counts
    // for the tier it had; working-set data keeps its mark and lands one generation younger.
    tiers_[static_cast<std::size_t>(tier(hit.refs + 1, hit.workingset))].refaulted += pages(cache, hit.bytes);
    if (!hit.workingset) return {hit.bytes, cold};
    return {hit.bytes, Placement{.list = ListKind::Active, .referenced = false, .bits = static_cast<std::uint8_t>(cold.bits | kWorkingset)}};
  }

  bool spares_files_being_written() const noexcept override { return false; }
  std::int64_t reclaim(PageCache& cache, std::int64_t amount, FileId excluded) override {
    CacheWalks walks = cache.walks();
    int protect_above = tier_index();
    std::int64_t evicted = 0;
    int idle = 0;  // retirements in a row after which nothing was evicted
    while (evicted < amount) {
      const std::int64_t before = evicted;
      // evict_folios over the oldest generation from its tail; sort_folio's rules in order.
      for (BlockId id = walks.first(ListKind::Inactive); id != kNoBlock && evicted < amount;) {
        const BlockId next = walks.next(id);
        const Block& block = walks.block(id);
        const std::uint8_t bits = block.policy_bits;
        const int t = tier(bits);
        const bool lazily_promoted = refs(bits) == kMaxRefs && workingset(bits);
        if (block.file == excluded) {
          id = next;  // stays where it is
          continue;
        }
        if (lazily_promoted || t > protect_above) {
          if (!lazily_promoted) tiers_[static_cast<std::size_t>(t)].protected_pages += pages(cache, block.size);
          promote(walks, id, bits & kWorkingset);
        } else if (block.state != BlockState::Clean) {
          promote(walks, id, static_cast<std::uint8_t>((bits & kWorkingset) | kReclaim));
        } else {
          evicted += walks.evict(id, amount - evicted);
        }
        id = next;
      }
      if (evicted >= amount || walks.first(ListKind::Active) == kNoBlock) break;
      idle = evicted > before ? 0 : idle + 1;
      if (idle == 2) break;  // the rest is dirty, in writeback or protected: the flusher's turn
      retire(walks);
      protect_above = tier_index();
    }
    return evicted;
  }
  std::int64_t evictable(const PageCache& cache) const noexcept override {
    return cache.list(ListKind::Inactive).bytes(BlockState::Clean) + cache.list(ListKind::Active).bytes(BlockState::Clean);
  }

  void evicted(const PageCache& cache, const Evicted& data) override {
    tiers_[static_cast<std::size_t>(tier(data.bits))].evicted += pages(cache, data.bytes);
    const auto kept = static_cast<std::uint8_t>(std::max(refs(data.bits) - 1, 0));
    FileShadows& shadows = shadows_[data.file];
    if (data.offset == kNoOffset) {
      if (!shadows.whole.empty() && shadows.whole.back().refs == kept && shadows.whole.back().workingset == workingset(data.bits)) {
        shadows.whole.back().bytes += data.bytes;
      } else {
        shadows.whole.push_back({data.bytes, kept, workingset(data.bits)});
      }
    } else {
      forget(shadows.ranged, data.offset, data.offset + data.bytes);
      shadows.ranged.emplace(data.offset, RangedShadow{data.offset + data.bytes, kept, workingset(data.bits)});
    }
  }
  void dropped(const PageCache&, FileId file) override { shadows_.erase(file); }

  // folio_end_writeback -> folio_rotate_reclaimable: the reclaim mark cleared, to the oldest tail.
  bool rotates_written_back() const noexcept override { return true; }
  std::optional<std::uint8_t> written_back(const Block& block) const noexcept override {
    if ((block.policy_bits & kReclaim) == 0) return std::nullopt;
    return static_cast<std::uint8_t>(block.policy_bits & ~kReclaim);
  }

 private:
  struct TierCounts {
    std::int64_t refaulted = 0;
    std::int64_t evicted = 0;
    std::int64_t protected_pages = 0;
    std::int64_t avg_refaulted = 0;
    std::int64_t avg_total = 0;
  };

  static std::int64_t pages(const PageCache& cache, std::int64_t bytes) noexcept {
    const std::int64_t page = cache.ranges().page_size();
    return (bytes + page - 1) / page;
  }

  // folio_inc_gen: to the next generation's head, references cleared, the working set kept.
  static void promote(CacheWalks& walks, BlockId id, std::uint8_t bits) {
    walks.move_to_back(id, ListKind::Active, false);
    walks.set_bits(id, bits);
  }

  // try_to_inc_min_seq, then inc_max_seq (kswapd ages while fewer than four generations are
  // open: should_run_aging below DEF_PRIORITY): the next generation becomes the oldest, the
  // counters are folded into their averages (reset_ctrl_pos), and the shadows of the retired
  // generation are no longer recent (max_seq has moved MAX_NR_GENS past their token).
  void retire(CacheWalks& walks) {
    for (BlockId id = walks.first(ListKind::Active); id != kNoBlock;) {
      const BlockId next = walks.next(id);
      walks.move_to_back(id, ListKind::Inactive, false);
      id = next;
    }
    for (TierCounts& t : tiers_) {
      t.avg_refaulted = (t.avg_refaulted + t.refaulted) / 2;
      t.avg_total = (t.avg_total + t.evicted + t.protected_pages) / 2;
      t.refaulted = t.evicted = t.protected_pages = 0;
    }
    shadows_.clear();
  }

  // get_tier_idx: tiers above the first whose refault ratio exceeds tier 0's are protected.
  int tier_index() const noexcept {
    auto ctrl = [&](int t, std::int64_t gain) {
      const TierCounts& c = tiers_[static_cast<std::size_t>(t)];
      return Ctrl{c.avg_refaulted + c.refaulted, c.avg_total + c.protected_pages + c.evicted, gain};
    };
    const Ctrl set_point = ctrl(0, 2);
    for (int t = 1; t < kTiers; ++t) {
      if (!at_or_below(set_point, ctrl(t, 3), batch_)) return t - 1;
    }
    return kTiers - 1;
  }

  // Forgets the shadows of [from, to), cutting those that stick out.
  static void forget(std::map<std::int64_t, RangedShadow>& ranged, std::int64_t from, std::int64_t to) {
    auto at = ranged.upper_bound(from);
    if (at != ranged.begin() && std::prev(at)->second.end > from) {
      --at;
      if (at->first < from) {
        const RangedShadow whole = at->second;
        at->second.end = from;
        if (whole.end > to) {
          ranged.emplace(to, RangedShadow{whole.end, whole.refs, whole.workingset});
          return;
        }
        ++at;
      }
    }
    while (at != ranged.end() && at->first < to) {
      if (at->second.end > to) {
        const RangedShadow rest = at->second;
        ranged.erase(at);
        ranged.emplace(to, rest);
        return;
      }
      at = ranged.erase(at);
    }
  }

  std::int64_t batch_;  // refault_batch
  std::array<TierCounts, kTiers> tiers_{};
  std::unordered_map<FileId, FileShadows> shadows_;
};

}  // namespace

extern const PolicyRegistration kMglruPolicy{
    .declaration = {
        .name = "mglru",
        .doc = "the kernel's multi-generation LRU (lru_gen): reads counted into tiers, refault feedback protects hot tiers, "
               "shadows bring the working set back a generation younger; the kernel's writeback",
        .parameters = kParameters,
        .preset_of = {},
    },
    .make = [](const CacheSettings& settings) -> std::unique_ptr<Policy> { return std::make_unique<MglruPolicy>(settings); },
};

}  // namespace pagecache::cache
