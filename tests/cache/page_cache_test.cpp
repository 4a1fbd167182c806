// PageCache operations on small, hand-built states: each expectation is derived in a comment
// from docs/model.md §2-§3 (and docs/wrench-cache.md for the paper profile's readings).
#include "cache/page_cache.hpp"

#include <pagecache/error.hpp>

#include <catch2/catch.hpp>

#include <vector>

using namespace pagecache;
using namespace pagecache::cache;

namespace {

struct Seen {
  FileId file;
  std::int64_t size;
  BlockState state;
  friend bool operator==(const Seen&, const Seen&) = default;
};

std::vector<Seen> blocks(const PageCache& cache, ListKind kind) {
  std::vector<Seen> out;
  for (const Block& b : cache.list(kind).blocks()) out.push_back({b.file, b.size, b.state});
  return out;
}

constexpr auto C = BlockState::Clean;
constexpr auto D = BlockState::Dirty;
constexpr auto W = BlockState::Writeback;
constexpr auto I = ListKind::Inactive;
constexpr auto A = ListKind::Active;

}  // namespace

TEST_CASE("memory is conserved: total = free + anonymous + cached + reserved", "[page_cache]") {
  PageCache cache(1000, CacheSettings::paper());
  cache.set_checking(true);
  cache.allocate_anonymous(100);
  cache.add_clean(0, 200, 0.0);
  cache.add_dirty(1, 50, 0.0);
  cache.reserve(30);
  const MemoryState m = cache.memory();
  CHECK(m.total == 1000);
  CHECK(m.anonymous == 100);
  CHECK(m.cached == 250);
  CHECK(m.dirty == 50);
  CHECK(m.reserved == 30);
  CHECK(m.free == 1000 - 100 - 250 - 30);
  CHECK_THROWS_AS(cache.allocate_anonymous(m.free + 1), SimulationError);
}

TEST_CASE("re-reading cached data moves it to the active list, clean data merged", "[page_cache]") {
  // File 0 has clean 100, dirty 50, clean 100 on the inactive list. Re-reading 250 bytes
  // takes them in order: the dirty block moves on its own (keeping its entry time), the two
  // clean ones become one block of 200 appended after it.
  PageCache cache(10000, CacheSettings::paper());
  cache.set_checking(true);
  cache.add_clean(0, 100, 1.0);
  cache.add_dirty(0, 50, 2.0);
  cache.add_clean(0, 100, 3.0);
  cache.add_clean(1, 500, 4.0);  // keeps the lists balanced (active <= 2 x inactive)
  cache.reaccess(0, 250, 5.0);
  CHECK(blocks(cache, I) == std::vector<Seen>{{1, 500, C}});
  CHECK(blocks(cache, A) == std::vector<Seen>{{0, 50, D}, {0, 200, C}});
  CHECK(cache.list(A).blocks().front().entry_time == 2.0);
}

TEST_CASE("a block read in part is split and only the part read moves", "[page_cache]") {
  // 70 of a 100-byte block: the first 70 go to the active list, 30 stay inactive.
  PageCache cache(10000, CacheSettings::paper());
  cache.add_clean(0, 100, 0.0);
  cache.add_clean(1, 400, 0.0);
  cache.reaccess(0, 70, 1.0);
  CHECK(blocks(cache, I) == std::vector<Seen>{{0, 30, C}, {1, 400, C}});
  CHECK(blocks(cache, A) == std::vector<Seen>{{0, 70, C}});
  CHECK(cache.file(0).in(I) == 30);
  CHECK(cache.file(0).in(A) == 70);
}

TEST_CASE("balancing keeps the active list at most twice the inactive list", "[page_cache]") {
  // Inactive 100, then 600 re-read: active 600 > 2 x 0 left inactive. Moving x bytes gives
  // 600 - x <= 2x: x = 200, taken from the least recently used end of the active list.
  PageCache cache(10000, CacheSettings::paper());
  cache.add_clean(0, 300, 0.0);
  cache.add_clean(1, 300, 0.0);
  cache.reaccess(0, 300, 1.0);
  cache.reaccess(1, 300, 2.0);
  CHECK(cache.list(A).bytes() == 400);
  CHECK(cache.list(I).bytes() == 200);
  CHECK(blocks(cache, I) == std::vector<Seen>{{0, 200, C}});
  CHECK(blocks(cache, A) == std::vector<Seen>{{0, 100, C}, {1, 300, C}});
}

TEST_CASE("flushing takes the least recently used dirty data, skipping the excluded file", "[page_cache]") {
  // Inactive: D0 100, C1 50, D1 100, D2 100. flush(150, excluding file 0): D1 whole, then 50
  // of D2; D2 is split. In the paper profile the flushed part of the split block moves to
  // the MRU end of the inactive list; in the kernel's it stays in place.
  for (const bool in_place : {false, true}) {
    CacheSettings settings = CacheSettings::paper();
    settings.set("flush_splits_in_place", in_place);  // the kernel policy's, the others as the paper's
    PageCache cache(10000, settings);
    cache.set_checking(true);
    cache.add_dirty(0, 100, 0.0);
    cache.add_clean(1, 50, 0.0);
    cache.add_dirty(1, 100, 0.0);
    cache.add_dirty(2, 100, 0.0);
    std::vector<PageCache::Flushed> taken;
    CHECK(cache.flush(150, 0, taken) == 150);
    REQUIRE(taken.size() == 2);
    CHECK(taken[0].file == 1);
    CHECK(taken[0].bytes == 100);
    CHECK(taken[1].file == 2);
    CHECK(taken[1].bytes == 50);
    if (in_place) {
      CHECK(blocks(cache, I) == std::vector<Seen>{{0, 100, D}, {1, 50, C}, {1, 100, W}, {2, 50, W}, {2, 50, D}});
    } else {
      CHECK(blocks(cache, I) == std::vector<Seen>{{0, 100, D}, {1, 50, C}, {1, 100, W}, {2, 50, D}, {2, 50, W}});
    }
    // Data in writeback is neither dirty nor evictable; it is clean once written.
    CHECK(cache.memory().dirty == 150);
    CHECK(cache.memory().writeback == 150);
    CHECK(cache.evict(1000, kNoFile) == 50);
    for (const auto& t : taken) cache.end_writeback(t);
    CHECK(cache.memory().writeback == 0);
    CHECK(cache.file(2).dirty == 50);
    CHECK(cache.file(1).cached() == 100);
  }
}

TEST_CASE("each file's part of a flush is a write of its own, ending on its own", "[page_cache]") {
  // The flusher writes a group's parts one after the other: the first ending leaves the
  // second's data in writeback, however many blocks the files hold.
  PageCache cache(10000, CacheSettings::paper());
  cache.set_checking(true);
  for (const FileId file : {0, 1, 0, 1}) cache.add_clean(file, 10, 0.0);
  cache.add_dirty(0, 100, 1.0);
  cache.add_dirty(1, 100, 1.0);
  std::vector<PageCache::Flushed> taken;
  CHECK(cache.flush(200, kNoFile, taken) == 200);
  REQUIRE(taken.size() == 2);
  CHECK(taken[0].token != taken[1].token);
  cache.end_writeback(taken[0]);
  CHECK(cache.writeback(0) == 0);
  CHECK(cache.writeback(1) == 100);
  cache.end_writeback(taken[1]);
  CHECK(cache.memory().writeback == 0);
  CHECK(cache.memory().dirty == 0);
}

TEST_CASE("eviction frees clean data from the least recently used end", "[page_cache]") {
  // Inactive: C0 100, D1 100, C2 100; active: C3 100. evict(150, excluding 2): C0 whole, and
  // then nothing else is clean on the inactive list but the excluded file. The paper profile
  // goes on to the clean active data in place (50 of C3 evicted, 50 stay active); the kernel
  // settings age the active list: C3 moves to the inactive list and 50 of it are reclaimed.
  for (const bool inactive_only : {false, true}) {
    CacheSettings settings = CacheSettings::paper();
    settings.set("reclaim_inactive_only", inactive_only);  // the kernel policy's, the others as the paper's
    PageCache cache(10000, settings);
    cache.set_checking(true);
    cache.add_clean(0, 100, 0.0);
    cache.add_dirty(1, 100, 0.0);
    cache.add_clean(2, 100, 0.0);
    cache.add_clean(3, 100, 0.0);
    cache.reaccess(3, 100, 0.0);
    CHECK(cache.evict(150, 2) == 150);
    CHECK(cache.file(0).cached() == 0);
    CHECK(cache.file(1).cached() == 100);
    CHECK(cache.file(2).cached() == 100);
    CHECK(cache.file(3).cached() == 50);
    CHECK(cache.file(3).in(ListKind::Active) == (inactive_only ? 0 : 50));
  }
}

TEST_CASE("the periodic flusher takes expired dirty blocks one at a time, inactive list first", "[page_cache]") {
  PageCache cache(10000, CacheSettings::paper());
  cache.set_checking(true);
  cache.add_dirty(0, 100, 0.0);   // expired at cutoff 10
  cache.add_dirty(1, 100, 20.0);  // not expired
  cache.add_dirty(2, 100, 5.0);   // expired
  const auto first = cache.flush_expired_block(10.0);
  CHECK(first.file == 0);
  const auto second = cache.flush_expired_block(10.0);
  CHECK(second.file == 2);
  CHECK(cache.flush_expired_block(10.0).bytes == 0);
  cache.end_writeback(first);
  cache.end_writeback(second);
  CHECK(cache.memory().dirty == 100);
  CHECK(cache.file(1).dirty == 100);
}

TEST_CASE("expired data that appears where the flusher's last search has passed is still taken first", "[page_cache]") {
  // Under one cutoff each search resumes where the last one stopped. Here the last one
  // stopped on the active list (behind file 1, not expired, it took file 0); then file 2
  // becomes dirty at the cutoff itself (as with dirty_expire = 0) on the inactive list, which
  // the order puts before the active list: it is the next one taken.
  PageCache cache(10000, CacheSettings::paper());
  cache.set_checking(true);
  cache.add_clean(9, 1000, 0.0);  // keeps the lists balanced without moving anything
  cache.add_dirty(1, 100, 11.0);
  cache.reaccess(1, 100, 12.0);
  cache.add_dirty(0, 100, 1.0);
  cache.reaccess(0, 100, 13.0);
  REQUIRE(blocks(cache, A) == std::vector<Seen>{{1, 100, D}, {0, 100, D}});
  const auto first = cache.flush_expired_block(5.0);
  CHECK(first.file == 0);
  cache.add_dirty(2, 100, 5.0);
  const auto second = cache.flush_expired_block(5.0);
  CHECK(second.file == 2);
  CHECK(cache.flush_expired_block(5.0).bytes == 0);  // file 1 is not expired
}

TEST_CASE("with expire_oldest_first the periodic flusher takes the oldest expired data first", "[page_cache]") {
  // Dirty data of ages 0 s (file 0, inactive), 5 s (file 2, read twice: active) and 20 s
  // (file 1). At cutoff 10 the paper's order takes the inactive list first (file 0, then file
  // 2); oldest first takes file 0 then file 2 as well, but when the active data is older
  // (file 3 at -5 s, read twice) it comes first, wherever it sits on the lists. Splitting a
  // dirty block keeps its pieces in place by age.
  for (const bool oldest_first : {true, false}) {
    CacheSettings settings = CacheSettings::kernel();
    settings.set("expire_oldest_first", oldest_first);
    settings.set("two_touch_activation", false);  // one re-read activates
    PageCache cache(10000, settings);
    cache.set_checking(true);
    cache.add_dirty(0, 100, 0.0);
    cache.add_dirty(1, 100, 20.0);
    cache.add_dirty(3, 100, -5.0);
    cache.reaccess(3, 100, 21.0);  // file 3 now on the active list, still dirty since -5 s
    const auto first = cache.flush_expired_block(10.0);
    CHECK(first.file == (oldest_first ? 3u : 0u));
    const auto second = cache.flush_expired_block(10.0);
    CHECK(second.file == (oldest_first ? 0u : 3u));
    CHECK(cache.flush_expired_block(10.0).bytes == 0);  // file 1 is not expired
    cache.end_writeback(first);
    cache.end_writeback(second);
    CHECK(cache.memory().dirty == 100);
  }
}

TEST_CASE("the dirty thresholds' base is free + cached (kernel) or free + clean cached (paper)", "[page_cache]") {
  PageCache paper(1000, CacheSettings::paper());
  PageCache kernel(1000, CacheSettings::kernel());
  for (PageCache* cache : {&paper, &kernel}) {
    cache->allocate_anonymous(300);
    cache->add_clean(0, 200, 0.0);
    cache->add_dirty(1, 100, 0.0);
  }
  CHECK(kernel.policy().dirtyable(kernel) == 400 + 300);
  CHECK(paper.policy().dirtyable(paper) == 400 + 300 - 100);
}

TEST_CASE("with balance_after_every_change an eviction rebalances the lists at once", "[page_cache]") {
  // Inactive 600 (file 0), then 300 of file 1 re-read: active 300. Evicting 500 leaves
  // inactive 100, active 300 > 2 x 100. The kernel settings rebalance now: moving x makes
  // 300 - x <= 2 (100 + x), x = 34. WRENCH-cache balances only after reads.
  for (const bool always : {true, false}) {
    CacheSettings settings = CacheSettings::paper();
    settings.set("balance_after_every_change", always);  // the kernel policy's, the others as the paper's
    PageCache cache(10000, settings);
    cache.set_checking(true);
    cache.add_clean(0, 600, 0.0);
    cache.add_clean(1, 300, 0.0);
    cache.reaccess(1, 300, 1.0);
    CHECK(cache.evict(500, kNoFile) == 500);
    CHECK(cache.list(A).bytes() == (always ? 266 : 300));
    CHECK(cache.list(I).bytes() == (always ? 134 : 100));
  }
}

TEST_CASE("two-touch activation: written data read once stays inactive, data read twice is activated", "[page_cache]") {
  // Kernel behaviour (mark_page_accessed): file 0 is written (not referenced), file 1 read
  // from disk (referenced by that read). Reading each once more: file 0 is only marked
  // referenced and stays inactive; file 1 is activated. A third read activates file 0. The
  // paper's model activates at the first re-read.
  for (const bool two_touch : {true, false}) {
    CacheSettings settings = CacheSettings::kernel();
    settings.set("two_touch_activation", two_touch);
    settings.set("balance_after_every_change", false);
    PageCache cache(10000, settings);
    cache.set_checking(true);
    cache.add_dirty(0, 100, 0.0);
    cache.add_read(1, 100, 0.0);
    cache.add_clean(2, 1000, 0.0);  // keeps active <= 2 x inactive
    cache.reaccess(0, 100, 1.0);
    cache.reaccess(1, 100, 1.0);
    CHECK(cache.file(0).in(ListKind::Inactive) == (two_touch ? 100 : 0));
    CHECK(cache.file(1).in(ListKind::Active) == 100);
    cache.reaccess(0, 100, 2.0);
    CHECK(cache.file(0).in(ListKind::Active) == 100);
  }
}

TEST_CASE("files being written keep their pages while other clean data is left", "[page_cache]") {
  // Inactive, oldest first: file 0 (100, clean, being written), file 1 (100, clean). With the
  // protection, evicting 100 takes file 1 although file 0 is older; evicting 50 more must then
  // take file 0. Without it, plain LRU order: file 0 goes first.
  for (const bool protect : {true, false}) {
    CacheSettings settings = CacheSettings::kernel();
    settings.set("protect_files_being_written", protect);
    PageCache cache(10000, settings);
    cache.set_checking(true);
    cache.add_clean(0, 100, 0.0);
    cache.add_clean(1, 100, 0.0);
    cache.set_being_written(0, true);
    CHECK(cache.evict(100, kNoFile) == 100);
    CHECK(cache.file(0).cached() == (protect ? 100 : 0));
    CHECK(cache.file(1).cached() == (protect ? 0 : 100));
    CHECK(cache.evict(50, kNoFile) == 50);
    CHECK(cache.file(0).cached() + cache.file(1).cached() == 50);
    cache.set_being_written(0, false);
  }
}

TEST_CASE("a read in chunks touches each page once: its cursor skips what it marked, and starts over when stale", "[page_cache][activation]") {
  // Kernel, file 0 written as three dirty blocks of 100 (not referenced). Three chunks of 100
  // with the cursor: each marks the next block; none is activated. A block written afterwards
  // comes after the last one touched: the next chunk marks it. A fourth chunk then starts
  // past the end, finds nothing left, and falls back to the file's oldest data (read twice
  // now: activated). Without the cursor every chunk would start at the oldest block: the
  // second would activate it.
  CacheSettings settings = CacheSettings::kernel();
  settings.set("balance_after_every_change", false);
  PageCache cache(10000, settings);
  cache.set_checking(true);
  cache.add_clean(9, 1000, 0.0);  // keeps active <= 2 x inactive
  for (int i = 0; i < 3; ++i) cache.add_dirty(0, 100, i);
  ReadCursor cursor;
  for (int i = 0; i < 3; ++i) cursor = cache.reaccess(0, 100, 10.0 + i, cursor);
  CHECK(cache.file(0).in(A) == 0);
  CHECK(cursor.after);
  cache.add_dirty(0, 100, 20.0);
  cursor = cache.reaccess(0, 100, 21.0, cursor);
  CHECK(cache.file(0).in(A) == 0);
  cache.reaccess(0, 100, 22.0, cursor);
  CHECK(cache.file(0).in(A) == 100);
  CHECK(blocks(cache, A) == std::vector<Seen>{{0, 100, D}});

  // A cursor naming a block that has gone (evicted, its id reused by another file's data)
  // starts at the file's oldest data again.
  PageCache other(10000, settings);
  other.set_checking(true);
  other.add_clean(9, 1000, 0.0);
  other.add_read(1, 100, 0.0);  // referenced by this read
  other.add_clean(1, 100, 0.0);  // a second block of file 1, not referenced
  const ReadCursor stale = other.reaccess(1, 50, 1.0, {});  // activates half the first block
  REQUIRE(stale.block != kNoBlock);
  CHECK(other.file(1).in(A) == 50);
  other.evict(1000 + 150, kNoFile);  // everything clean and inactive goes, the cursor's block too
  other.add_clean(2, 100, 2.0);      // may take the freed id
  other.add_read(1, 100, 3.0);
  other.reaccess(1, 100, 4.0, stale);  // the new block of file 1, referenced: activated
  CHECK(other.file(1).in(A) == 150);
}
