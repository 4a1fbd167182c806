// Randomised check of files held by byte range against a reference model of single bytes: each
// cached byte is a unit (file, offset, referenced) on one of two plain vectors in LRU order,
// every operation written as the obvious loop over them. Reads of random ranges, evictions,
// application memory, whole-file data added before a file is held by range, files dropped:
// after every step the lists, expanded byte by byte from PageCache's blocks, must equal the
// reference's exactly (order, offsets, marks), with every invariant checked by PageCache.
//
// Bytes stand for pages: PageCache's ranges are in bytes, the page rounding is the
// IoController's. Block boundaries are not compared, only what they hold, so that merging and
// splitting are free to differ. Not covered: reclaim_inactive_only, whose active-list aging
// moves the oldest active block whole (its boundary is the implementation's choice, not the
// model's; page_cache_random_test covers it on whole files).
#include "cache/page_cache.hpp"

#include <pagecache/error.hpp>

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <algorithm>
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
  friend bool operator==(const Unit&, const Unit&) = default;
};

class Reference {
 public:
  Reference(std::int64_t total, const CacheSettings& s, bool first_touch)
      : total_(total),
        lru_(s.policy == "lru"),
        two_touch_(!lru_ && s.get("two_touch_activation")),
        balance_always_(!lru_ && s.get("balance_after_every_change")),
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
    for (std::int64_t i = 0; i < bytes; ++i) inactive.push_back({f, -1, first_touch_});
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
    for (std::int64_t o = offset; o < offset + bytes; ++o) {
      auto in = [&](std::vector<Unit>& list) {
        return std::find_if(list.begin(), list.end(), [&](const Unit& u) { return u.file == f && u.offset == o; });
      };
      if (auto it = in(active); it != active.end()) {
        Unit u = *it;
        active.erase(it);
        u.referenced = false;
        active.push_back(u);
      } else if (auto jt = in(inactive); jt != inactive.end()) {
        if (two_touch_ && !jt->referenced) {
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
        inactive.push_back({f, o, first_touch_});
        ++missing;
      }
    }
    balance();
    settle();
    return missing;
  }

  // Clean data least recently used first, skipping `excluded`: the inactive list, then (the
  // kernel policy without reclaim_inactive_only) the active list.
  std::int64_t evict(std::int64_t amount, FileId excluded) {
    std::int64_t evicted = 0;
    for (auto* list : {&inactive, &active}) {
      if (list == &active && lru_) break;
      for (auto it = list->begin(); it != list->end() && evicted < amount;) {
        if (it->file == excluded) {
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

  void drop(FileId f) {
    for (auto* list : {&inactive, &active}) std::erase_if(*list, [&](const Unit& u) { return u.file == f; });
    settle();
  }

 private:
  std::int64_t total_;
  bool lru_;
  bool two_touch_;
  bool balance_always_;
  bool first_touch_;
};

std::vector<Unit> expand(const PageCache& cache, ListKind kind) {
  std::vector<Unit> units;
  const LruList& list = cache.list(kind);
  for (BlockId id = list.front(); id != kNoBlock; id = list.next(id)) {
    const Block& b = cache.block(id);
    REQUIRE(b.state == BlockState::Clean);
    for (std::int64_t i = 0; i < b.size; ++i) units.push_back({b.file, b.ranged ? cache.ranges().offset(id) + i : -1, b.referenced});
  }
  return units;
}

void compare(const PageCache& cache, const Reference& ref, std::uint64_t step) {
  INFO("step " << step);
  REQUIRE(expand(cache, ListKind::Inactive) == ref.inactive);
  REQUIRE(expand(cache, ListKind::Active) == ref.active);
  REQUIRE(cache.free() == ref.free());
  for (FileId f = 0; f < kFiles; ++f) REQUIRE(cache.ranged(f) == ref.ranged[f]);
}

std::uint64_t run_random(const CacheSettings& settings, std::uint64_t seed, int steps) {
  constexpr std::int64_t kTotal = 160;
  PageCache cache(kTotal, settings);
  cache.set_checking(true);
  Reference ref(kTotal, settings, cache.policy().read_is_first_touch());
  std::mt19937_64 rng(seed);
  auto pick = [&](std::int64_t lo, std::int64_t hi) { return std::uniform_int_distribution<std::int64_t>(lo, hi)(rng); };
  std::uint64_t reads = 0;
  for (int step = 0; step < steps; ++step) {
    const auto file = static_cast<FileId>(pick(0, kFiles - 1));
    const double now = step;
    switch (pick(0, 9)) {
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
        const std::int64_t missing = bytes - cache.cached_in(file, offset, bytes);
        REQUIRE(missing == bytes - ref.cached_in(file, offset, bytes));
        if (missing > cache.free()) REQUIRE(cache.evict(missing - cache.free(), spared) == ref.evict(missing - ref.free(), spared));
        // The eviction may have taken some of the range itself.
        if (bytes - cache.cached_in(file, offset, bytes) > cache.free()) break;
        REQUIRE(cache.read_range(file, offset, bytes, now) == ref.read(file, offset, bytes));
        ++reads;
        break;
      }
      case 4: {
        const std::int64_t amount = pick(1, 60);
        const FileId excluded = pick(0, 1) ? file : kNoFile;
        REQUIRE(cache.evict(amount, excluded) == ref.evict(amount, excluded));
        break;
      }
      case 5: {  // application memory
        if (pick(0, 1)) {
          const std::int64_t bytes = pick(0, std::min<std::int64_t>(cache.free(), 40));
          cache.allocate_anonymous(bytes);
          ref.anonymous += bytes;
        } else {
          const std::int64_t bytes = pick(0, cache.anonymous());
          cache.release_anonymous(bytes);
          ref.anonymous -= bytes;
        }
        break;
      }
      case 6: {  // whole-file data of a file not (yet) held by range
        if (ref.ranged[file]) break;
        const std::int64_t bytes = std::min<std::int64_t>(pick(1, 30), std::min(cache.free(), kFileSize - cache.cached(file)));
        cache.add_read(file, bytes, now);
        ref.add_whole(file, bytes);
        break;
      }
      case 7:
        if (pick(0, 3) == 0) {  // the file is deleted: it comes back as a file not held by range
          cache.drop_file(file);
          ref.drop(file);
        }
        break;
      default: {  // a read of the whole file by range: sequential, in a few requests
        if (!ref.ranged[file] || cache.free() < kFileSize) break;
        for (std::int64_t offset = 0; offset < kFileSize; offset += 16) {
          REQUIRE(cache.read_range(file, offset, 16, now) == ref.read(file, offset, 16));
          ++reads;
        }
        break;
      }
    }
    compare(cache, ref, static_cast<std::uint64_t>(step));
  }
  return reads;
}

}  // namespace

TEST_CASE("files held by range agree with a reference of single bytes (paper profile)", "[page_cache][ranges][random]") {
  std::uint64_t reads = 0;
  for (std::uint64_t seed : {11u, 12u}) reads += run_random(CacheSettings::paper(), seed, 150000);
  CHECK(reads > 100000);
}

TEST_CASE("files held by range agree with a reference of single bytes (kernel settings, two-touch activation)",
          "[page_cache][ranges][random]") {
  CacheSettings settings = CacheSettings::kernel();
  settings.set("reclaim_inactive_only", false);
  std::uint64_t reads = 0;
  for (std::uint64_t seed : {13u, 14u}) reads += run_random(settings, seed, 150000);
  CHECK(reads > 100000);
}

TEST_CASE("files held by range agree with a reference of single bytes (lru policy)", "[page_cache][ranges][random]") {
  CacheSettings settings = CacheSettings::kernel();
  settings.policy = "lru";
  std::uint64_t reads = 0;
  for (std::uint64_t seed : {15u, 16u}) reads += run_random(settings, seed, 150000);
  CHECK(reads > 100000);
}
