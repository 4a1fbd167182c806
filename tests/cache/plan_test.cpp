// Plans without a simulator: the paper's Algorithms 2 and 3 (docs/model.md §4) on small, hand-built
// page caches. Each expectation is derived in a comment from the algorithm and the settings;
// where a plan is carried out, the test does what the IoController does (evict, flush) and plans
// again.
#include "cache/plan.hpp"

#include <pagecache/cache_settings.hpp>

#include <catch2/catch.hpp>

#include <vector>

namespace pagecache::cache {
namespace {

constexpr auto I = ListKind::Inactive;
constexpr auto A = ListKind::Active;

// Writes back everything `flush` took, as the controller does once the device writes end.
void end_all(PageCache& cache, const std::vector<PageCache::Flushed>& taken) {
  for (const auto& part : taken) cache.end_writeback(part);
}

}  // namespace

// --- The dirty thresholds ---------------------------------------------------------------------

TEST_CASE("the dirty thresholds are fractions of dirtyable memory, truncated to bytes", "[plan]") {
  // Kernel: dirtyable = free + cached + reserved = 1003 on an empty 1003-byte host.
  // thresh = 0.2 x 1003 = 200.6 -> 200; background = 0.1 x 1003 = 100.3 -> 100;
  // freerun = (100 + 200) / 2 = 150.
  PageCache cache(1003, CacheSettings::kernel());
  cache.set_checking(true);
  const DirtyLimits l = dirty_limits(cache);
  CHECK(l.thresh == 200);
  CHECK(l.background == 100);
  CHECK(l.freerun == 150);
}

TEST_CASE("dirtyable memory: free + cached + copies in flight (kernel), or free + clean (paper)", "[plan]") {
  // 1000 bytes: 300 anonymous, 200 clean, 100 dirty of which 40 in writeback, 50 reserved for a
  // copy in flight: free = 1000 - 300 - 300 - 50 = 350. Ratios 0.4 and 0.1 (the paper's).
  // On:  dirtyable = 350 + 300 + 50 = 700: thresh 280, background 70, freerun 175.
  // Off: dirtyable = 350 + 300 - 60 - 40 = 550: thresh 220, background 55, freerun 137.
  // Room under the threshold: thresh - (dirty + writeback) = 280 - 100 and 220 - 100.
  for (const bool dirtyable_memory : {true, false}) {
    CacheSettings s = CacheSettings::paper();
    s.set("dirtyable_memory", dirtyable_memory);  // the kernel policy's, the others as the paper's
    PageCache cache(1000, s);
    cache.set_checking(true);
    cache.allocate_anonymous(300);
    cache.add_clean(0, 200, 0.0);
    cache.add_dirty(1, 100, 1.0);
    std::vector<PageCache::Flushed> taken;
    REQUIRE(cache.flush(40, kNoFile, taken) == 40);
    cache.reserve(50);
    REQUIRE(cache.free() == 350);
    const DirtyLimits l = dirty_limits(cache);
    if (dirtyable_memory) {
      CHECK(l.thresh == 280);
      CHECK(l.background == 70);
      CHECK(l.freerun == 175);
      CHECK(room_under_dirty_threshold(cache) == 180);
    } else {
      CHECK(l.thresh == 220);
      CHECK(l.background == 55);
      CHECK(l.freerun == 137);
      CHECK(room_under_dirty_threshold(cache) == 120);
    }
  }
}

TEST_CASE("a background ratio not below the dirty ratio is clamped to half the threshold", "[plan]") {
  // 1000 bytes, nothing cached: dirtyable 1000, thresh = 0.2 x 1000 = 200. A background ratio
  // of 0.5 or 0.2 (equal counts too) gives thresh / 2 = 100, not 500 or 200.
  for (const double background_ratio : {0.5, 0.2}) {
    CacheSettings s = CacheSettings::kernel();
    s.dirty_ratio = 0.2;
    s.dirty_background_ratio = background_ratio;
    PageCache cache(1000, s);
    const DirtyLimits l = dirty_limits(cache);
    CHECK(l.thresh == 200);
    CHECK(l.background == 100);
    CHECK(l.freerun == 150);
  }
  // An odd threshold halves down: 0.2 x 1005 = 201, background 100, freerun (100 + 201) / 2 = 150.
  CacheSettings s = CacheSettings::kernel();
  s.dirty_background_ratio = 0.2;
  PageCache odd(1005, s);
  CHECK(dirty_limits(odd).thresh == 201);
  CHECK(dirty_limits(odd).background == 100);
  CHECK(dirty_limits(odd).freerun == 150);
}

// --- Room in memory ---------------------------------------------------------------------------

TEST_CASE("room: evictable is every inactive byte (paper) or the clean inactive ones (kernel)", "[plan]") {
  // 1000 bytes: 400 anonymous; file 0 read (300) and 100 of it read again, which activates it
  // under both settings (the kernel's first read marks it referenced); file 1 dirty (100).
  // Inactive: 200 clean + 100 dirty; active: 100; free = 200.
  // Room for 700: evict 700 - 200 = 500; flush 700 - 200 - evictable, where evictable is
  // 300 (paper) -> 200, or 200 (kernel) -> 300. Active data counts in neither.
  for (const bool paper : {true, false}) {
    PageCache cache(1000, paper ? CacheSettings::paper() : CacheSettings::kernel());
    cache.set_checking(true);
    cache.allocate_anonymous(400);
    cache.add_read(0, 300, 0.0);
    cache.reaccess(0, 100, 1.0);
    cache.add_dirty(1, 100, 2.0);
    REQUIRE(cache.file(0).in(A) == 100);
    REQUIRE(cache.list(I).bytes() == 300);
    REQUIRE(cache.free() == 200);
    const RoomPlan room = plan_room(cache, 700);
    CHECK(room.flush == (paper ? 200 : 300));
    CHECK(room.evict == 500);
    CHECK_FALSE(room.fits);
    // Exactly what is free fits: nothing to evict or flush.
    const RoomPlan exact = plan_room(cache, 200);
    CHECK(exact.fits);
    CHECK(exact.evict == 0);
    CHECK(exact.flush == (paper ? -300 : -200));
    CHECK_FALSE(plan_room(cache, 201).fits);
    CHECK(plan_room(cache, 201).evict == 1);
  }
}

TEST_CASE("a read spares the file being read only under the paper's settings", "[plan]") {
  PageCache kernel(1000, CacheSettings::kernel());
  PageCache paper(1000, CacheSettings::paper());
  CHECK(spared_by_read(kernel, 7) == kNoFile);
  CHECK(spared_by_read(paper, 7) == 7);
}

TEST_CASE("nothing can be freed while no writeback and no copy into the cache is in flight", "[plan]") {
  // Dirty data alone does not count: a writer could flush it itself, nobody else will.
  PageCache cache(1000, CacheSettings::kernel());
  cache.set_checking(true);
  cache.add_dirty(0, 100, 0.0);
  CHECK(nothing_can_be_freed(cache));
  std::vector<PageCache::Flushed> taken;
  cache.flush(100, kNoFile, taken);
  CHECK_FALSE(nothing_can_be_freed(cache));  // the writeback's end will make 100 clean
  end_all(cache, taken);
  CHECK(nothing_can_be_freed(cache));
  cache.reserve(10);
  CHECK_FALSE(nothing_can_be_freed(cache));  // the copy's end will make room to flush
  cache.commit_dirty(0, 10, 1.0);
  CHECK(nothing_can_be_freed(cache));
}

// --- Algorithm 2: a chunk read ----------------------------------------------------------------

TEST_CASE("a read takes from the device what is not cached, within the chunk", "[plan]") {
  // 1000 bytes; file 0 (500 bytes) all cached; file 2 (600 bytes) 500 cached. free = 0.
  PageCache cache(1000, CacheSettings::kernel());
  cache.set_checking(true);
  cache.add_clean(0, 500, 0.0);
  cache.add_clean(2, 500, 0.0);
  // All cached: nothing from the device; the application's copy is all it needs.
  const ReadPlan cached = plan_read(cache, {.file = 0, .file_size = 500, .bytes = 200, .anonymous = 200});
  CHECK(cached.from_disk == 0);
  CHECK(cached.from_cache == 200);
  CHECK(cached.required == 200);
  // Nothing cached of file 1 (10000 bytes): the whole chunk, 200, from the device; the copy
  // and the new cache data take 400, all of it to evict.
  const ReadPlan uncached = plan_read(cache, {.file = 1, .file_size = 10000, .bytes = 200, .anonymous = 200});
  CHECK(uncached.from_disk == 200);
  CHECK(uncached.from_cache == 0);
  CHECK(uncached.required == 400);
  CHECK(uncached.room.evict == 400);
  // 600 - 500 = 100 not cached: 100 from the device, 100 from the cache.
  const ReadPlan partly = plan_read(cache, {.file = 2, .file_size = 600, .bytes = 200, .anonymous = 200});
  CHECK(partly.from_disk == 100);
  CHECK(partly.from_cache == 100);
  CHECK(partly.required == 300);
  // A server's read (no application copy here): only the new cache data.
  CHECK(plan_read(cache, {.file = 1, .file_size = 10000, .bytes = 200, .anonymous = 0}).required == 200);
}

TEST_CASE("evicting for a read may take the file's own data: more then comes from the device", "[plan]") {
  // 1000 bytes: 200 anonymous; file 0 (400 bytes) has 300 cached, the oldest data; file 1 has
  // 100. free = 400. A read of the whole file in one chunk (400, and a 400-byte copy):
  // from_disk = 400 - 300 = 100, required 500, evict 100, nothing to flush (all clean).
  const ReadRequest request{.file = 0, .file_size = 400, .bytes = 400, .anonymous = 400};
  for (const bool kernel : {true, false}) {
    PageCache cache(1000, kernel ? CacheSettings::kernel() : CacheSettings::paper());
    cache.set_checking(true);
    cache.allocate_anonymous(200);
    cache.add_clean(0, 300, 0.0);
    cache.add_clean(1, 100, 1.0);
    const ReadPlan first = plan_read(cache, request);
    CHECK(first.from_disk == 100);
    CHECK(first.required == 500);
    CHECK(first.room.evict == 100);
    CHECK(first.room.flush <= 0);
    CHECK_FALSE(first.room.fits);
    CHECK(cache.evict(first.room.evict, first.spared) == 100);
    const ReadPlan second = plan_read(cache, request);
    if (kernel) {
      // Reclaim takes the least recently used data, the file's own: 200 of it left, so
      // from_disk = 200 and required = 600 > free = 500. The room made is not enough.
      CHECK(cache.file(0).cached() == 200);
      CHECK(second.from_disk == 200);
      CHECK(second.required == 600);
      CHECK_FALSE(second.room.fits);
      CHECK(second.room.evict == 100);
    } else {
      // The paper spares the file being read: file 1 goes, and the first plan holds.
      CHECK(cache.file(0).cached() == 300);
      CHECK(second.from_disk == 100);
      CHECK(second.room.fits);
    }
  }
}

TEST_CASE("a read flushes first when the inactive data is dirty (kernel), not under the paper's count", "[plan]") {
  // 1000 bytes: 200 anonymous, file 1 dirty (500, inactive): free 300. Reading 300 of an
  // uncached file with a 300-byte copy: required 600, evict 300.
  // Kernel: evictable = clean inactive = 0, so flush 600 - 300 - 0 = 300.
  // Paper: evictable = every inactive byte = 500, so flush 600 - 300 - 500 = -200: none,
  // though evicting finds nothing clean.
  const ReadRequest request{.file = 0, .file_size = 300, .bytes = 300, .anonymous = 300};
  auto build = [](PageCache& cache) {
    cache.set_checking(true);
    cache.allocate_anonymous(200);
    cache.add_dirty(1, 500, 0.0);
  };
  PageCache paper(1000, CacheSettings::paper());
  build(paper);
  const ReadPlan p = plan_read(paper, request);
  CHECK(p.required == 600);
  CHECK(p.room.flush == -200);
  CHECK(paper.evict(p.room.evict, p.spared) == 0);
  CHECK_FALSE(plan_read(paper, request).room.fits);
  CHECK(nothing_can_be_freed(paper));  // the controller gives up rather than wait

  PageCache kernel(1000, CacheSettings::kernel());
  build(kernel);
  ReadPlan k = plan_read(kernel, request);
  CHECK(k.room.flush == 300);
  CHECK(k.room.evict == 300);
  std::vector<PageCache::Flushed> taken;
  REQUIRE(kernel.flush(k.room.flush, k.spared, taken) == 300);
  // In writeback the data is neither dirty nor evictable: still 300 to flush.
  CHECK(plan_read(kernel, request).room.flush == 300);
  end_all(kernel, taken);
  // Written back, it is clean inactive data: 600 - 300 - 300 = 0 to flush, 300 to evict.
  k = plan_read(kernel, request);
  CHECK(k.room.flush == 0);
  CHECK(k.room.evict == 300);
  CHECK(kernel.evict(k.room.evict, k.spared) == 300);
  CHECK(plan_read(kernel, request).room.fits);
}

// --- Algorithm 3: a chunk write in writeback mode ---------------------------------------------

TEST_CASE("under the dirty threshold a write evicts for what the threshold allows, then copies what is free", "[plan]") {
  // Paper settings, 1000 bytes: 250 anonymous, file 1 clean (600), file 0 dirty (100): free 50.
  // dirtyable = 50 + 700 - 100 = 650, thresh = 0.4 x 650 = 260, remain_dirty = 160.
  // A 200-byte chunk: evict min(200, 160) - 50 = 110; copy min(200, 50) = 50 as memory is now.
  PageCache cache(1000, CacheSettings::paper());
  cache.set_checking(true);
  cache.allocate_anonymous(250);
  cache.add_clean(1, 600, 0.0);
  cache.add_dirty(0, 100, 1.0);
  const WriteStart start = plan_write_start(cache, 200);
  CHECK(start.under_threshold);
  CHECK(start.evict == 110);
  CHECK(start.to_cache == 50);
  REQUIRE(cache.evict(start.evict, 0) == 110);
  // After the eviction free = 160 and dirtyable is the same 650: copy 160 now, 40 later.
  const WriteStart after = plan_write_start(cache, 200);
  CHECK(after.under_threshold);
  CHECK(after.to_cache == 160);
  // The copy takes its pages: the loop's first pass, 40 left, flushes 40 and must evict 40.
  cache.reserve(after.to_cache);
  const WriteStep step = plan_write_step(cache, 40);
  CHECK(step.flush == 40);
  CHECK(step.evict == 40);
  CHECK(step.to_cache == 0);
}

TEST_CASE("a write chunk may overshoot the dirty threshold as far as memory is free", "[plan]") {
  // Paper settings, 1000 bytes, file 0 dirty (100): free 900, dirtyable 900, thresh 360,
  // remain_dirty 260. A 500-byte chunk: evict 260 - 900 < 0, copy min(500, 900) = 500 > 260.
  PageCache cache(1000, CacheSettings::paper());
  cache.add_dirty(0, 100, 0.0);
  const WriteStart start = plan_write_start(cache, 500);
  CHECK(start.under_threshold);
  CHECK(start.evict == -640);
  CHECK(start.to_cache == 500);
}

TEST_CASE("at or over the dirty threshold nothing of a write chunk goes to the cache at once", "[plan]") {
  // Kernel settings, 1000 bytes: dirtyable = free + cached = 1000 whatever is dirty,
  // thresh = 200. Dirty 200: remain_dirty 0; dirty 250: -50.
  for (const std::int64_t dirty : {200, 250}) {
    PageCache cache(1000, CacheSettings::kernel());
    cache.add_dirty(0, dirty, 0.0);
    CHECK(room_under_dirty_threshold(cache) == 200 - dirty);
    const WriteStart start = plan_write_start(cache, 100);
    CHECK_FALSE(start.under_threshold);
    CHECK(start.evict == 0);
    CHECK(start.to_cache == 0);
  }
}

TEST_CASE("a write's loop copies no sliver under a page unless it is all that is left", "[plan]") {
  // Free memory of 4095 bytes, one short of a page: with 10000 bytes left nothing is copied
  // (flush 10000, evict 10000 - 4095 = 5905); with 4095 or 3000 left, all of it is.
  constexpr std::int64_t kTotal = 1'000'000;
  PageCache sliver(kTotal, CacheSettings::paper());
  sliver.allocate_anonymous(kTotal - (kPageSize - 1));
  const WriteStep step = plan_write_step(sliver, 10000);
  CHECK(step.flush == 10000);
  CHECK(step.evict == 5905);
  CHECK(step.to_cache == 0);
  CHECK(plan_write_step(sliver, kPageSize - 1).to_cache == kPageSize - 1);
  CHECK(plan_write_step(sliver, 3000).to_cache == 3000);
  // A whole page free is worth a copy.
  PageCache page(kTotal, CacheSettings::paper());
  page.allocate_anonymous(kTotal - kPageSize);
  CHECK(plan_write_step(page, 10000).to_cache == kPageSize);
  // Plenty free: the writer still flushes as much as it has left to write.
  PageCache roomy(kTotal, CacheSettings::paper());
  CHECK(plan_write_step(roomy, 100).flush == 100);
  CHECK(plan_write_step(roomy, 100).to_cache == 100);
}

}  // namespace pagecache::cache
