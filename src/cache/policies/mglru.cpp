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

#include "cache/file_ranges.hpp"
#include "cache/policies/kernel_writeback.hpp"

#include <pagecache/cache_policies.hpp>

#include <algorithm>
#include <array>
#include <deque>
#include <iterator>
#include <limits>
#include <unordered_map>
#include <vector>

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
struct Mark {
  std::uint8_t refs = 0;
  bool workingset = false;
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
    Shadow hit;
    if (offset == kNoOffset) {
      const auto found = whole_.find(file);
      if (found == whole_.end() || found->second.empty()) return {bytes, cold};
      Shadow& oldest = found->second.front();
      hit = {std::min(bytes, oldest.bytes), oldest.refs, oldest.workingset};
      if ((oldest.bytes -= hit.bytes) == 0) found->second.pop_front();
    } else {
      if (!ranged_.tracked(file)) return {bytes, cold};
      const FileRanges::Located at = ranged_.at_or_after(file, offset);
      if (at.id == kNoBlock || at.offset > offset) {
        // No shadow at `offset`: cold up to the next one.
        return {at.id == kNoBlock ? bytes : std::min(bytes, at.offset - offset), cold};
      }
      const Mark mark = marks_[at.id];
      hit = {std::min(offset + bytes, at.end) - offset, mark.refs, mark.workingset};
      forget(file, at, offset, offset + hit.bytes);
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
    if (data.offset == kNoOffset) {
      std::deque<Shadow>& shadows = whole_[data.file];
      if (!shadows.empty() && shadows.back().refs == kept && shadows.back().workingset == workingset(data.bits)) {
        shadows.back().bytes += data.bytes;
      } else {
        shadows.push_back({data.bytes, kept, workingset(data.bits)});
      }
    } else {
      if (!ranged_.tracked(data.file)) {
        ranged_.track(data.file);
        ranged_files_.push_back(data.file);
      }
      forget(data.file, ranged_.at_or_after(data.file, data.offset), data.offset, data.offset + data.bytes);
      add(data.file, data.offset, data.offset + data.bytes, Mark{kept, workingset(data.bits)});
    }
  }
  void dropped(const PageCache&, FileId file) override {
    whole_.erase(file);
    if (ranged_.tracked(file)) forget(file, ranged_.at_or_after(file, 0), 0, std::numeric_limits<std::int64_t>::max());
  }

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
    whole_.clear();
    for (FileId file : ranged_files_) forget(file, ranged_.at_or_after(file, 0), 0, std::numeric_limits<std::int64_t>::max());
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

  // A shadow of [from, to) of a file held by range.
  void add(FileId file, std::int64_t from, std::int64_t to, Mark mark) {
    BlockId id = static_cast<BlockId>(marks_.size());
    if (free_.empty()) {
      marks_.push_back(mark);
    } else {
      id = free_.back();
      free_.pop_back();
      marks_[id] = mark;
    }
    ranged_.insert(file, id, from, to - from);
  }
  // Forgets the shadows of [from, to) of `file`, cutting those that stick out; `at` is
  // ranged_.at_or_after(file, from).
  void forget(FileId file, FileRanges::Located at, std::int64_t from, std::int64_t to) {
    while (at.id != kNoBlock && at.offset < to) {
      const FileRanges::Located next = at.end < to ? ranged_.at_or_after(file, at.end) : FileRanges::Located{};
      if (at.offset < from) {
        ranged_.resize(file, at.id, from - at.offset);
        if (at.end > to) add(file, to, at.end, marks_[at.id]);
      } else if (at.end > to) {
        const Mark mark = marks_[at.id];
        ranged_.erase(file, at.id);
        free_.push_back(at.id);
        add(file, to, at.end, mark);
      } else {
        ranged_.erase(file, at.id);
        free_.push_back(at.id);
      }
      at = next;
    }
  }

  std::int64_t batch_;  // refault_batch
  std::array<TierCounts, kTiers> tiers_{};
  // Shadows (lru_gen_eviction): of files held whole, by file in eviction order, oldest first;
  // of files held by range, disjoint byte ranges in a B+ tree per file, as the page cache's
  // blocks are (a std::map cost a cache miss a level under random reads), marks by id.
  std::unordered_map<FileId, std::deque<Shadow>> whole_;
  FileRanges ranged_;
  std::vector<Mark> marks_;
  std::vector<BlockId> free_;
  std::vector<FileId> ranged_files_;  // tracked in ranged_
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
