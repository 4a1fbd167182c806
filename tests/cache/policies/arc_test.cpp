// The arc policy: T1 = the inactive list, T2 = the active list, ghost lists B1 and B2 of its own,
// and the target p that ghost hits move. Every expected value is worked out by hand from ARC's
// rules as arc.cpp states them (the comment of each case gives the steps).
#include "cache/page_cache.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <string>

using namespace pagecache;
using namespace pagecache::cache;

namespace {

CacheSettings named(const std::string& policy) {
  CacheSettings s = CacheSettings::kernel();
  s.policy = policy;
  return s;
}

// A read of all `bytes` of `file` as IoController does it: its cached part re-accessed, the rest
// evicted for if memory is short and brought in from the device. Returns the bytes read from it.
std::int64_t read(PageCache& cache, FileId file, std::int64_t bytes, double now) {
  const std::int64_t cached = cache.file(file).cached();
  if (cached > 0) cache.reaccess(file, cached, now);
  const std::int64_t missing = bytes - cached;
  if (missing > cache.free()) REQUIRE(cache.evict(missing - cache.free(), kNoFile) == missing - cache.free());
  cache.add_read(file, missing, now);
  return missing;
}

}  // namespace

TEST_CASE("arc: a re-read activates, and a scan of data read once evicts only data read once", "[policy][arc]") {
  // Memory 1000. Cold file 9 (200) read, hot file 0 (400) read and re-read: T2 = {0: 400},
  // T1 = {9: 200} (active 400 <= 2 x 200: no balancing). A scan of files 1..8 (100 each): 1..4
  // fill the free 400; 5..8 each evict 100. p stays 0 (no ghost is ever hit), so every eviction
  // takes T1's least recently used data: file 9, then files 1 and 2. The kernel (two-touch
  // activation, inactive list first) evicts the same; lru's one list loses half of file 0.
  for (const std::string policy : {"arc", "kernel", "lru"}) {
    INFO(policy);
    PageCache cache(1000, named(policy));
    cache.set_checking(true);
    CHECK(cache.policy().name() == policy);
    read(cache, 9, 200, 0.0);
    read(cache, 0, 400, 0.0);
    read(cache, 0, 400, 1.0);
    if (policy != "lru") CHECK(cache.file(0).in(ListKind::Active) == 400);
    for (FileId f = 1; f <= 8; ++f) read(cache, f, 100, 2.0 + f);
    CHECK(cache.totals().evicted == 400);
    CHECK(cache.file(0).cached() == (policy == "lru" ? 200 : 400));
    CHECK(cache.file(9).cached() == 0);
    CHECK(cache.file(1).cached() == (policy == "lru" ? 100 : 0));
    CHECK(cache.file(2).cached() == (policy == "lru" ? 100 : 0));
    for (FileId f = 3; f <= 8; ++f) CHECK(cache.file(f).cached() == 100);
  }
}

TEST_CASE("arc: ghost hits raise p until reclaim takes the stale twice-read data the kernel keeps", "[policy][arc]") {
  // Memory 1000 (c = 1000). Cold X = file 9 (200) read; H = file 0 (400) read and re-read (T2).
  // Then files 1, 2, 3, 4 (200 each) read in a loop, three rounds: 800 bytes, more than the 600
  // T1 has room for beside H.
  // arc: r1, r2 fill memory. r3, r4 evict X, 1 (T1 above p = 0): B1 = X, 1. r5 (file 1) evicts
  //   2, then its miss hits 200 B1 bytes, B2 empty: p = 200. r6 evicts 3 (T1 600, 400 above p),
  //   hits: p = 400. r7 evicts 4 (200 above p), hits: p = 600. r8 (file 4): T1 = 600 = p, so
  //   reclaim takes T2's LRU 200: half of H. Its miss hits B1 (B1 400 > B2 200: delta 200):
  //   p = 800. Files 1..4 are all cached now: r9..r12 hit. Read from devices: 8 x 200.
  // kernel: the inactive list's 600 holds three of the four files; H, active, is never aged
  //   while inactive clean data is left: every read misses, H stays. Read: 12 x 200.
  // lru: r3 evicts X, r4 the older half of H (one list); r5..r12 hit. Read: 4 x 200.
  struct Expected {
    std::string policy;
    std::int64_t h_after_r4, h_after_r8, device_bytes, evicted;
  };
  for (const Expected& e : {Expected{"arc", 400, 200, 1600, 1200}, Expected{"kernel", 400, 400, 2400, 2000},
                            Expected{"lru", 200, 200, 800, 400}}) {
    INFO(e.policy);
    PageCache cache(1000, named(e.policy));
    cache.set_checking(true);
    read(cache, 9, 200, 0.0);
    read(cache, 0, 400, 0.0);
    read(cache, 0, 400, 1.0);
    std::int64_t device = 0;
    for (int r = 1; r <= 12; ++r) {
      device += read(cache, static_cast<FileId>((r - 1) % 4 + 1), 200, 1.0 + r);
      if (r == 4) CHECK(cache.file(0).cached() == e.h_after_r4);
      if (r == 8) CHECK(cache.file(0).cached() == e.h_after_r8);
    }
    CHECK(cache.file(9).cached() == 0);
    CHECK(device == e.device_bytes);
    CHECK(cache.totals().evicted == e.evicted);
  }
}

TEST_CASE("arc: the ghost lists hold at most the cache's size, oldest first; a dropped file's are forgotten", "[policy][arc]") {
  // Memory 900 (c = 900). Files A=1, B=2, C=3 (300 each) read; B and C re-read: T2 = B, C
  // (600 <= 2 x 300), T1 = A. Then new files, 300 each, read once; each evicts T1's 300 (p = 0):
  // D=4 evicts A (B1 = A), E=5 evicts D (B1 = A, D: 600).
  // remembered: A read back now evicts E (B1 = A, D, E: 900, at the cap) and hits A's 300 ghost
  //   bytes: p = 300. Then I=8 read: T1 (A, 300) is not above p: reclaim takes T2's LRU, B.
  // trimmed: F=6 evicts E (B1 900), G=7 evicts F: B1 would be 1200, so A's ghosts, the oldest,
  //   go. A read back evicts G and hits nothing: p stays 0. I read: T1 (A) is above p: A goes,
  //   B stays.
  // dropped: A deleted (drop_file) before it is read back: its ghosts go with it, as trimmed.
  enum class Case { Remembered, Trimmed, Dropped };
  for (const Case c : {Case::Remembered, Case::Trimmed, Case::Dropped}) {
    INFO(static_cast<int>(c));
    PageCache cache(900, named("arc"));
    cache.set_checking(true);
    for (FileId f : {1, 2, 3}) read(cache, f, 300, 0.0);
    read(cache, 2, 300, 1.0);
    read(cache, 3, 300, 1.0);
    REQUIRE(cache.file(2).in(ListKind::Active) == 300);
    REQUIRE(cache.file(3).in(ListKind::Active) == 300);
    for (FileId f : {4, 5}) read(cache, f, 300, 2.0);
    if (c == Case::Trimmed) {
      for (FileId f : {6, 7}) read(cache, f, 300, 3.0);
    }
    if (c == Case::Dropped) cache.drop_file(1);
    CHECK(read(cache, 1, 300, 4.0) == 300);
    read(cache, 8, 300, 5.0);
    const bool remembered = c == Case::Remembered;
    CHECK(cache.file(1).cached() == (remembered ? 300 : 0));
    CHECK(cache.file(2).cached() == (remembered ? 0 : 300));
    CHECK(cache.file(3).cached() == 300);
    CHECK(cache.file(8).cached() == 300);
  }
}

TEST_CASE("arc: a miss on B2 ghosts lowers p, scaled by B1 / B2, so reclaim keeps twice-read data again", "[policy][arc]") {
  // Memory 900, as "remembered" above: after A read back and I read, p = 300, T1 = A, I (600),
  // T2 = C (300), B1 = D, E (600, evicted 2nd and 3rd), B2 = B (300, evicted 4th).
  // B's first 150 read back: reclaim takes 150 of T1's 300 above p, A's first 150 (B1 = D, E,
  //   A150: 750, 1050 in all, so D's oldest 150 forgotten: B1 = 600). The miss hits 150 B2
  //   bytes: p = 300 - 150 x max(1, 600 / 300) = 0 (unscaled, 150 would be left). T1 = A150,
  //   I, B150 (600).
  // control: a new file N=9 read instead (150): A's first 150 evicted likewise, no ghost hit,
  //   p stays 300. T1 = A150, I, N150.
  // K=10 (600 bytes) read: evicts 600. p = 0: all from T1 (A150, I, B150), C stays (p = 150
  //   would take T1's 450 above it, then 150 of C). p = 300: T1's 300 above it (A150, I's first
  //   150), then T2's 300: C.
  for (const bool b2_hit : {true, false}) {
    INFO(b2_hit);
    PageCache cache(900, named("arc"));
    cache.set_checking(true);
    for (FileId f : {1, 2, 3}) read(cache, f, 300, 0.0);
    read(cache, 2, 300, 1.0);
    read(cache, 3, 300, 1.0);
    for (FileId f : {4, 5, 1, 8}) read(cache, f, 300, 2.0);
    REQUIRE(cache.file(2).cached() == 0);
    REQUIRE(cache.file(1).cached() == 300);
    CHECK(read(cache, b2_hit ? 2 : 9, 150, 3.0) == 150);
    CHECK(cache.file(1).cached() == 150);
    read(cache, 10, 600, 4.0);
    CHECK(cache.file(1).cached() == 0);
    CHECK(cache.file(8).cached() == (b2_hit ? 0 : 150));
    CHECK(cache.file(b2_hit ? 2 : 9).cached() == (b2_hit ? 0 : 150));
    CHECK(cache.file(3).cached() == (b2_hit ? 300 : 0));
    CHECK(cache.file(10).cached() == 600);
  }
}
