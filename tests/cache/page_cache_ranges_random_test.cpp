// Randomised check of files held by byte range against a reference model of single bytes: each
// cached byte is a unit (file, offset, referenced, state, entry time, write token) on one of
// two plain vectors in LRU order, every operation written as the obvious loop over them. Reads
// and writes of random ranges, flushes with their writes ended out of order, evictions,
// application memory, whole-file data added before a file is held by range, files dropped:
// after every step the lists, expanded byte by byte from PageCache's blocks, must equal the
// reference's exactly (order, offsets, marks), with every invariant checked by PageCache.
//
// Bytes stand for pages: PageCache's ranges are in bytes, the page rounding is the
// IoController's. Block boundaries are not compared, only what they hold, so that merging and
// splitting are free to differ. Not covered: reclaim_inactive_only, whose active-list aging
// moves the oldest active block whole (its boundary is the implementation's choice, not the
// model's; page_cache_random_test covers it on whole files), and flushes that move a block
// they split (flush_splits_in_place off: which bytes move depends on where the block began).
#include "cache/page_cache.hpp"

#include <pagecache/error.hpp>

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <map>
#include <optional>
#include <cstdint>
#include <random>
#include <vector>

using namespace pagecache;
using namespace pagecache::cache;

namespace {

constexpr int kFiles = 4;
constexpr std::int64_t kFileSize = 64;

struct Unit {
  FileId file;
  std::int64_t offset;  // -1: whole-file data of a file not yet held by range
  bool referenced;
  BlockState state = BlockState::Clean;
  double entry = 0.0;         // dirty: when it became dirty
  std::uint64_t token = 0;    // in writeback: the flush writing it
  std::uint8_t bits = 0;      // the policy's marks (mglru: refs, working set, reclaim)
  friend bool operator==(const Unit&, const Unit&) = default;
};

}  // namespace

// A failure prints each byte as file:offset, its state, mark, entry time and token.
template <>
struct Catch::StringMaker<Unit> {
  static std::string convert(const Unit& u) {
    return fmt::format("{}:{}{}{}@{}#{}b{}", u.file, u.offset, "cdw"[static_cast<int>(u.state)], u.referenced ? "*" : "", u.entry, u.token, u.bits);
  }
};

namespace {

class Reference {
 public:
  Reference(std::int64_t total, const CacheSettings& s, bool first_touch)
      : total_(total),
        lru_(s.policy == "lru"),
        clock_(s.policy == "clock"),
        mglru_(s.policy == "mglru"),
        batch_(mglru_ ? s.integer("refault_batch") : 0),
        two_touch_(!lru_ && !clock_ && !mglru_ && s.get("two_touch_activation")),
        splits_in_place_(lru_ || clock_ || mglru_ || s.get("flush_splits_in_place")),
        balance_always_(!lru_ && !clock_ && !mglru_ && s.get("balance_after_every_change")),
        first_touch_(first_touch) {}

  std::vector<Unit> inactive, active;
  std::int64_t anonymous = 0;
  std::vector<bool> ranged = std::vector<bool>(kFiles, false);

  std::int64_t cached() const { return static_cast<std::int64_t>(inactive.size() + active.size()); }
  std::int64_t free() const { return total_ - anonymous - cached(); }

  void settle() {
    if (balance_always_) balance();
  }
  void balance() {
    const auto excess = static_cast<std::int64_t>(active.size()) - 2 * static_cast<std::int64_t>(inactive.size());
    if (excess <= 0) return;
    const std::int64_t move = (excess + 2) / 3;
    for (std::int64_t i = 0; i < move; ++i) {
      Unit u = active.front();
      active.erase(active.begin());
      u.referenced = false;
      inactive.push_back(u);
    }
  }

  // Whole-file data read before the file is held by range.
  void add_whole(FileId f, std::int64_t bytes) {
    for (std::int64_t i = 0; i < bytes; ++i) {
      if (mglru_) arrive(f, -1, true);
      else inactive.push_back({f, -1, first_touch_});
    }
    settle();
  }

  // Its data takes offsets 0, 1, ... in LRU order, inactive list first.
  void track(FileId f) {
    if (ranged[f]) return;
    ranged[f] = true;
    std::int64_t offset = 0;
    for (auto* list : {&inactive, &active})
      for (Unit& u : *list)
        if (u.file == f) u.offset = offset++;
  }

  std::int64_t cached_in(FileId f, std::int64_t offset, std::int64_t bytes) const {
    std::int64_t n = 0;
    for (const auto* list : {&inactive, &active})
      for (const Unit& u : *list)
        if (u.file == f && u.offset >= offset && u.offset < offset + bytes) ++n;
    return n;
  }

  // The cached bytes of the range in offset order, each as the policy says; then the holes.
  std::int64_t read(FileId f, std::int64_t offset, std::int64_t bytes) {
    for (std::int64_t o = offset; o < offset + bytes && mglru_; ++o) {
      for (auto* list : {&inactive, &active})
        for (Unit& u : *list)
          if (u.file == f && u.offset == o) u.bits = (u.bits & 7) < 4 ? static_cast<std::uint8_t>(u.bits + 1) : u.bits | kWs;
    }
    for (std::int64_t o = offset; o < offset + bytes && !mglru_; ++o) {
      auto in = [&](std::vector<Unit>& list) {
        return std::find_if(list.begin(), list.end(), [&](const Unit& u) { return u.file == f && u.offset == o; });
      };
      if (auto it = in(active); it != active.end()) {
        Unit u = *it;
        active.erase(it);
        u.referenced = false;
        active.push_back(u);
      } else if (auto jt = in(inactive); jt != inactive.end()) {
        if (clock_ || (two_touch_ && !jt->referenced)) {  // CLOCK: a hit sets the bit, nothing moves
          jt->referenced = true;
          continue;
        }
        Unit u = *jt;
        inactive.erase(jt);
        u.referenced = false;
        (lru_ ? inactive : active).push_back(u);
      }
    }
    std::int64_t missing = 0;
    for (std::int64_t o = offset; o < offset + bytes; ++o) {
      if (cached_in(f, o, 1) == 0) {
        if (mglru_) arrive(f, o, true);
        else inactive.push_back({f, o, first_touch_});
        ++missing;
      }
    }
    if (!mglru_) balance();
    settle();
    return missing;
  }

  // Clean data least recently used first, skipping `excluded`: the inactive list, then (the
  // kernel policy without reclaim_inactive_only) the active list.
  std::int64_t evict(std::int64_t amount, FileId excluded) {
    if (mglru_) return evict_generations(amount, excluded);
    std::int64_t evicted = 0;
    if (clock_) {
      // The hand at the front: a referenced byte loses its bit and goes to the back (met again
      // at the end), the first unreferenced clean byte is evicted.
      for (std::size_t i = 0; i < inactive.size() && evicted < amount;) {
        Unit& u = inactive[i];
        if (u.file == excluded || u.state != BlockState::Clean) {
          ++i;
        } else if (u.referenced) {
          Unit back = u;
          back.referenced = false;
          inactive.erase(inactive.begin() + static_cast<std::ptrdiff_t>(i));
          inactive.push_back(back);
        } else {
          inactive.erase(inactive.begin() + static_cast<std::ptrdiff_t>(i));
          ++evicted;
        }
      }
      settle();
      return evicted;
    }
    for (auto* list : {&inactive, &active}) {
      if (list == &active && lru_) break;
      for (auto it = list->begin(); it != list->end() && evicted < amount;) {
        if (it->file == excluded || it->state != BlockState::Clean) {
          ++it;
        } else {
          it = list->erase(it);
          ++evicted;
        }
      }
    }
    settle();
    return evicted;
  }

  // Holes become dirty, clean and writeback bytes dirty again (entered now, to the MRU end),
  // dirty bytes stay as they are; in offset order.
  std::int64_t write(FileId f, std::int64_t offset, std::int64_t bytes, double now) {
    std::int64_t missing = 0;
    for (std::int64_t o = offset; o < offset + bytes; ++o) {
      const Unit dirty{f, o, false, BlockState::Dirty, now, 0};
      bool found = false;
      for (auto* list : {&inactive, &active}) {
        auto it = std::find_if(list->begin(), list->end(), [&](const Unit& u) { return u.file == f && u.offset == o; });
        if (it == list->end()) continue;
        found = true;
        if (it->state != BlockState::Dirty) {
          list->erase(it);
          inactive.push_back(dirty);
        }
      }
      if (!found) {
        inactive.push_back(dirty);
        ++missing;
      }
    }
    settle();
    return missing;
  }

  // Dirty bytes least recently used first, inactive list then active, up to `amount`; each
  // run of one file's bytes is a write of its own, with the next token from `first_token`.
  // In writeback a byte's write token takes the place of its entry time.
  std::int64_t flush(std::int64_t amount, std::uint64_t first_token) {
    std::int64_t flushed = 0;
    std::uint64_t token = first_token;
    FileId last = kNoFile;
    for (auto* list : {&inactive, &active})
      for (Unit& u : *list)
        if (u.state == BlockState::Dirty && flushed < amount) {
          if (last != kNoFile && u.file != last) ++token;
          last = u.file;
          u.state = BlockState::Writeback;
          u.token = token;
          u.entry = 0.0;
          ++flushed;
        }
    settle();
    return flushed;
  }

  void end_writeback(std::uint64_t token) {
    std::vector<Unit> rotated;  // mglru: marked for reclaim, to the oldest generation's tail
    for (auto* list : {&inactive, &active}) {
      for (auto it = list->begin(); it != list->end();) {
        if (it->state == BlockState::Writeback && it->token == token) {
          it->state = BlockState::Clean;
          it->token = 0;
          it->entry = 0.0;
          if (mglru_ && (it->bits & kReclaim)) {
            it->bits &= static_cast<std::uint8_t>(~kReclaim);
            rotated.push_back(*it);
            it = list->erase(it);
            continue;
          }
        }
        ++it;
      }
    }
    inactive.insert(inactive.begin(), rotated.begin(), rotated.end());
    settle();
  }

  void drop(FileId f) {
    for (auto* list : {&inactive, &active}) std::erase_if(*list, [&](const Unit& u) { return u.file == f; });
    std::erase_if(shadows_, [&](const auto& entry) { return entry.first.first == f; });
    whole_shadows_[f].clear();
    settle();
  }

  // --- mglru: each rule as the kernel states it, byte by byte ---------------------------------
  static constexpr std::uint8_t kWs = 8, kReclaim = 16;
  struct Shadow {
    std::uint8_t refs;  // refs less one
    bool ws;
  };
  static int tier(int refs, bool ws) { return ws ? 3 : refs <= 1 ? 0 : refs == 2 ? 1 : 2; }
  // A byte read from the device: a recent shadow counts its tier's refault; the working set
  // comes back in the next generation.
  void arrive(FileId f, std::int64_t o, bool demand) {
    Unit u{f, o, false};
    u.bits = demand ? 1 : 0;
    std::optional<Shadow> shadow;
    if (o < 0) {
      if (!whole_shadows_[f].empty()) {
        shadow = whole_shadows_[f].front();
        whole_shadows_[f].erase(whole_shadows_[f].begin());
      }
    } else if (auto it = shadows_.find({f, o}); it != shadows_.end()) {
      shadow = it->second;
      shadows_.erase(it);
    }
    if (shadow) refaulted_[tier(shadow->refs + 1, shadow->ws)] += 1;
    if (shadow && shadow->ws) {
      u.bits |= kWs;
      active.push_back(u);
    } else {
      inactive.push_back(u);
    }
  }
  int tier_index() const {
    auto at_or_below = [&](int t) {
      const std::int64_t sp_ref = avg_refaulted_[0] + refaulted_[0], sp_total = avg_total_[0] + protected_[0] + evicted_[0];
      const std::int64_t pv_ref = avg_refaulted_[t] + refaulted_[t], pv_total = avg_total_[t] + protected_[t] + evicted_[t];
      return pv_ref < batch_ || pv_ref * (sp_total + batch_) * 2 <= (sp_ref + 1) * pv_total * 3;
    };
    for (int t = 1; t < 4; ++t)
      if (!at_or_below(t)) return t - 1;
    return 3;
  }
  std::int64_t evict_generations(std::int64_t amount, FileId excluded) {
    int protect_above = tier_index();
    std::int64_t evicted = 0;
    int idle = 0;
    while (evicted < amount) {
      const std::int64_t before = evicted;
      for (std::size_t i = 0; i < inactive.size() && evicted < amount;) {
        Unit u = inactive[i];
        const int refs = u.bits & 7;
        const bool ws = (u.bits & kWs) != 0;
        const int t = tier(refs, ws);
        if (u.file == excluded) {
          ++i;
          continue;
        }
        inactive.erase(inactive.begin() + static_cast<std::ptrdiff_t>(i));
        if ((refs == 4 && ws) || t > protect_above) {
          if (!(refs == 4 && ws)) protected_[t] += 1;
          u.bits &= kWs;
          active.push_back(u);
        } else if (u.state != BlockState::Clean) {
          u.bits = static_cast<std::uint8_t>((u.bits & kWs) | kReclaim);
          active.push_back(u);
        } else {
          evicted_[t] += 1;
          const Shadow shadow{static_cast<std::uint8_t>(std::max(refs - 1, 0)), ws};
          if (u.offset < 0) whole_shadows_[u.file].push_back(shadow);
          else shadows_[{u.file, u.offset}] = shadow;
          ++evicted;
        }
      }
      if (evicted >= amount || active.empty()) break;
      idle = evicted > before ? 0 : idle + 1;
      if (idle == 2) break;
      // The oldest generation retired: the next one is the oldest, the counters folded.
      inactive.insert(inactive.end(), active.begin(), active.end());
      active.clear();
      for (int t = 0; t < 4; ++t) {
        avg_refaulted_[t] = (avg_refaulted_[t] + refaulted_[t]) / 2;
        avg_total_[t] = (avg_total_[t] + evicted_[t] + protected_[t]) / 2;
        refaulted_[t] = evicted_[t] = protected_[t] = 0;
      }
      shadows_.clear();
      for (auto& w : whole_shadows_) w.clear();
      protect_above = tier_index();
    }
    settle();
    return evicted;
  }

 private:
  std::int64_t total_;
  bool lru_;
  bool clock_;
  bool mglru_;
  std::int64_t batch_;
  bool two_touch_;
  std::map<std::pair<FileId, std::int64_t>, Shadow> shadows_;
  std::vector<std::vector<Shadow>> whole_shadows_ = std::vector<std::vector<Shadow>>(kFiles);
  std::array<std::int64_t, 4> refaulted_{}, evicted_{}, protected_{}, avg_refaulted_{}, avg_total_{};
 public:
  bool splits_in_place_;
 private:
  bool balance_always_;
  bool first_touch_;
};

std::vector<Unit> expand(const PageCache& cache, ListKind kind) {
  std::vector<Unit> units;
  const LruList& list = cache.list(kind);
  for (BlockId id = list.front(); id != kNoBlock; id = list.next(id)) {
    const Block& b = list.block(id);
    const bool dirty = b.state == BlockState::Dirty;  // in writeback its token holds the entry time's place
    const std::uint64_t token = b.state == BlockState::Writeback ? b.writeback_batch : 0;
    for (std::int64_t i = 0; i < b.size; ++i)
      units.push_back({b.file, b.ranged ? cache.ranges().offset(id) + i : -1, b.referenced, b.state, dirty ? b.entry_time : 0.0, token,
                       static_cast<std::uint8_t>(b.policy_bits)});
  }
  return units;
}

void compare(const PageCache& cache, const Reference& ref, std::uint64_t step) {
  INFO("step " << step);
  REQUIRE(expand(cache, ListKind::Inactive) == ref.inactive);
  REQUIRE(expand(cache, ListKind::Active) == ref.active);
  REQUIRE(cache.free() == ref.free());
  std::int64_t dirty = 0;
  for (const auto* list : {&ref.inactive, &ref.active})
    for (const Unit& u : *list) dirty += u.state == BlockState::Dirty;
  REQUIRE(cache.memory().dirty == dirty);
  for (FileId f = 0; f < kFiles; ++f) REQUIRE(cache.ranges().tracked(f) == ref.ranged[f]);
}

struct Counts {
  std::uint64_t reads = 0, writes = 0, flushes = 0;
  Counts& operator+=(const Counts& o) {
    reads += o.reads;
    writes += o.writes;
    flushes += o.flushes;
    return *this;
  }
};

// `numa_group`: two nodes, each operation from either, every file charged to one memory group
// and every eviction that group's: the reference, which knows no nodes, holds as a group's
// reclaim takes the host's least recently used data whatever its node.
Counts run_random(const CacheSettings& settings, std::uint64_t seed, int steps, bool numa_group = false) {
  constexpr std::int64_t kTotal = 160;
  PageCache cache(kTotal, settings, {.nodes = numa_group ? 2 : 1, .page_size = 1});  // bytes stand for pages
  cache.set_checking(true);
  const GroupId group = numa_group ? cache.add_group(kTotal) : kAnyGroup;
  Reference ref(kTotal, settings, cache.policy().read_is_first_touch());
  std::mt19937_64 rng(seed);
  auto pick = [&](std::int64_t lo, std::int64_t hi) { return std::uniform_int_distribution<std::int64_t>(lo, hi)(rng); };
  Counts counts;
  std::vector<std::vector<PageCache::Flushed>> in_flight;
  for (int step = 0; step < steps; ++step) {
    const auto file = static_cast<FileId>(pick(0, kFiles - 1));
    const double now = step;
    if (numa_group) {
      cache.touch_from(static_cast<NodeId>(pick(0, 1)));
      cache.charge_file(file, group);
    }
    switch (pick(0, 11)) {
      case 0:
      case 1:
      case 2:
      case 3: {  // a read of a range, after eviction makes room as the IoController does
        if (!ref.ranged[file]) {
          cache.track_ranges(file);
          ref.track(file);
        }
        const std::int64_t offset = pick(0, kFileSize - 1);
        const std::int64_t bytes = pick(1, kFileSize - offset);
        const FileId spared = pick(0, 1) ? file : kNoFile;
        const std::int64_t missing = bytes - cache.ranges().cached_in(file, offset, bytes);
        REQUIRE(missing == bytes - ref.cached_in(file, offset, bytes));
        if (missing > cache.free()) REQUIRE(cache.evict(missing - cache.free(), spared, group) == ref.evict(missing - ref.free(), spared));
        // The eviction may have taken some of the range itself.
        if (bytes - cache.ranges().cached_in(file, offset, bytes) > cache.free()) break;
        REQUIRE(cache.read_range(file, offset, bytes, now) == ref.read(file, offset, bytes));
        ++counts.reads;
        break;
      }
      case 4: {
        const std::int64_t amount = pick(1, 60);
        const FileId excluded = pick(0, 1) ? file : kNoFile;
        REQUIRE(cache.evict(amount, excluded, group) == ref.evict(amount, excluded));
        break;
      }
      case 5: {  // application memory
        if (pick(0, 1)) {
          const std::int64_t bytes = pick(0, std::min<std::int64_t>(cache.free(), 40));
          cache.allocate_anonymous(bytes);
          ref.anonymous += bytes;
        } else {
          const std::int64_t bytes = pick(0, cache.memory().anonymous);
          cache.release_anonymous(bytes);
          ref.anonymous -= bytes;
        }
        break;
      }
      case 6: {  // whole-file data of a file not (yet) held by range
        if (ref.ranged[file]) break;
        const std::int64_t bytes = std::min<std::int64_t>(pick(1, 30), std::min(cache.free(), kFileSize - cache.file(file).cached()));
        cache.add_read(file, bytes, now);
        ref.add_whole(file, bytes);
        break;
      }
      case 8: {  // a write of a range, its holes taking free memory
        if (!ref.ranged[file]) break;
        const std::int64_t offset = pick(0, kFileSize - 1);
        const std::int64_t bytes = pick(1, kFileSize - offset);
        if (bytes - cache.ranges().cached_in(file, offset, bytes) > cache.free()) break;
        REQUIRE(cache.write_range(file, offset, bytes, now) == ref.write(file, offset, bytes, now));
        ++counts.writes;
        break;
      }
      case 9: {  // a flush, its write ended later, in any order
        if (!ref.splits_in_place_) break;
        if (!in_flight.empty() && pick(0, 1)) {
          const auto i = static_cast<std::size_t>(pick(0, static_cast<std::int64_t>(in_flight.size()) - 1));
          for (const PageCache::Flushed& f : in_flight[i]) {
            cache.end_writeback(f);
            ref.end_writeback(f.token);
          }
          in_flight.erase(in_flight.begin() + static_cast<std::ptrdiff_t>(i));
          break;
        }
        const std::int64_t amount = pick(1, 50);
        std::vector<PageCache::Flushed> taken;
        const std::int64_t flushed = cache.flush(amount, kNoFile, taken);
        REQUIRE(flushed == ref.flush(amount, taken.empty() ? 0 : taken.front().token));
        in_flight.push_back(std::move(taken));
        ++counts.flushes;
        break;
      }
      case 7:
        // The file is deleted (its writes in flight first): it comes back as a file not held by range.
        if (pick(0, 3) == 0 && cache.writeback(file) == 0) {
          cache.drop_file(file);
          ref.drop(file);
        }
        break;
      default: {  // a read of the whole file by range: sequential, in a few requests
        if (!ref.ranged[file] || cache.free() < kFileSize) break;
        for (std::int64_t offset = 0; offset < kFileSize; offset += 16) {
          REQUIRE(cache.read_range(file, offset, 16, now) == ref.read(file, offset, 16));
          ++counts.reads;
        }
        break;
      }
    }
    compare(cache, ref, static_cast<std::uint64_t>(step));
  }
  return counts;
}

}  // namespace

// 1.2 million steps in all, the lists compared after each: every case must reach its reads,
// writes and flushes often, not be stuck short of memory.
TEST_CASE("files held by range agree with a reference of single bytes (paper profile)", "[page_cache][ranges][random]") {
  Counts counts;
  for (std::uint64_t seed : {11u, 12u}) counts += run_random(CacheSettings::paper(), seed, 200000);
  CHECK(counts.reads > 60000);
  CHECK(counts.writes > 15000);
}

TEST_CASE("files held by range agree with a reference of single bytes (kernel settings, two-touch activation)",
          "[page_cache][ranges][random]") {
  CacheSettings settings = CacheSettings::kernel();
  settings.set("reclaim_inactive_only", false);
  Counts counts;
  for (std::uint64_t seed : {13u, 14u}) counts += run_random(settings, seed, 200000);
  CHECK(counts.reads > 60000);
  CHECK(counts.writes > 15000);
  CHECK(counts.flushes > 10000);
}

TEST_CASE("files held by range agree with a reference of single bytes (lru policy)", "[page_cache][ranges][random]") {
  CacheSettings settings = CacheSettings::kernel();
  settings.policy = "lru";
  Counts counts;
  for (std::uint64_t seed : {15u, 16u}) counts += run_random(settings, seed, 200000);
  CHECK(counts.reads > 60000);
  CHECK(counts.writes > 15000);
  CHECK(counts.flushes > 10000);
}

TEST_CASE("files held by range agree with a reference of single bytes (clock policy)", "[page_cache][ranges][random][clock]") {
  CacheSettings settings = CacheSettings::kernel();
  settings.policy = "clock";
  Counts counts;
  counts += run_random(settings, 17u, 200000);
  CHECK(counts.reads > 30000);
  CHECK(counts.writes > 7500);
  CHECK(counts.flushes > 5000);
}

TEST_CASE("files held by range agree with a reference of single bytes (kernel settings, two nodes, a group's reclaim)",
          "[page_cache][ranges][random][numa][groups]") {
  // A group's reclaim on a host of two nodes takes its files' clean data in the list's order
  // across the nodes, through the group's heap of reclaimable files.
  CacheSettings settings = CacheSettings::kernel();
  settings.set("reclaim_inactive_only", false);
  Counts counts;
  counts += run_random(settings, 19u, 100000, true);
  CHECK(counts.reads > 15000);
  CHECK(counts.writes > 3500);
  CHECK(counts.flushes > 2500);
}

TEST_CASE("files held by range agree with a reference of single bytes (mglru policy)", "[page_cache][ranges][random][mglru]") {
  CacheSettings settings = CacheSettings::kernel();
  settings.policy = "mglru";
  Counts counts;
  counts += run_random(settings, 23u, 200000);
  CHECK(counts.reads > 30000);
  CHECK(counts.writes > 7500);
  CHECK(counts.flushes > 5000);
}

TEST_CASE("files held by range agree with a reference of single bytes (mglru policy, refaults counted from the first)",
          "[page_cache][ranges][random][mglru]") {
  // A batch of one page: the refault feedback protects tiers often even in a cache this small.
  CacheSettings settings = CacheSettings::kernel();
  settings.policy = "mglru";
  settings.set("refault_batch", std::int64_t{1});
  Counts counts;
  counts += run_random(settings, 31u, 100000);
  CHECK(counts.reads > 15000);
  CHECK(counts.writes > 3500);
}

TEST_CASE("files held by range agree with a reference of single bytes (mglru policy, two nodes, a group's reclaim)",
          "[page_cache][ranges][random][mglru][numa][groups]") {
  CacheSettings settings = CacheSettings::kernel();
  settings.policy = "mglru";
  Counts counts;
  counts += run_random(settings, 29u, 100000, true);
  CHECK(counts.reads > 15000);
  CHECK(counts.writes > 3500);
}
