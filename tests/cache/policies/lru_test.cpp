// The lru policy: one list, re-reads refresh, reclaim takes the least recently used clean data.
#include "cache/page_cache.hpp"

#include <catch2/catch.hpp>

using namespace pagecache;
using namespace pagecache::cache;

namespace {

CacheSettings lru() {
  CacheSettings s = CacheSettings::kernel();
  s.policy = "lru";
  return s;
}

}  // namespace

TEST_CASE("lru: a re-read moves data to the most recently used end, nothing is ever active", "[policy][lru]") {
  // Files 0, 1, 2 of 100 clean bytes each, in that order; file 0 re-read twice: the order is
  // 1, 2, 0, and evicting 150 takes file 1 and half of file 2.
  PageCache cache(10000, lru());
  cache.set_checking(true);
  CHECK(cache.policy().name() == "lru");
  for (FileId f = 0; f < 3; ++f) cache.add_read(f, 100, 0.0);
  cache.reaccess(0, 100, 1.0);
  cache.reaccess(0, 100, 2.0);
  CHECK(cache.list(ListKind::Active).bytes() == 0);
  CHECK(cache.evict(150, kNoFile) == 150);
  CHECK(cache.file(1).cached() == 0);
  CHECK(cache.file(2).cached() == 50);
  CHECK(cache.file(0).cached() == 100);
}

TEST_CASE("lru: a file read twice is evicted by a scan that the kernel's active list resists", "[policy][lru]") {
  // Cold file 2 (200 bytes) read; hot file 0 (400) read, then read again; then file 1 (400)
  // read once, and 600 bytes reclaimed. lru: the order is 2, 0, 1, so files 2 and 0 go.
  // kernel: the second read activated file 0 (active 400 <= 2 x inactive 200: no balancing);
  // reclaim takes the inactive data, files 2 and 1.
  for (const bool is_lru : {true, false}) {
    PageCache cache(10000, is_lru ? lru() : CacheSettings::kernel());
    cache.set_checking(true);
    cache.add_read(2, 200, 0.0);
    cache.add_read(0, 400, 0.0);
    cache.reaccess(0, 400, 1.0);
    cache.add_read(1, 400, 2.0);
    CHECK(cache.evict(600, kNoFile) == 600);
    CHECK(cache.file(2).cached() == 0);
    CHECK(cache.file(0).cached() == (is_lru ? 0 : 400));
    CHECK(cache.file(1).cached() == (is_lru ? 400 : 0));
  }
}

TEST_CASE("lru: dirty data re-read keeps its age and moves behind the clean data", "[policy][lru]") {
  // File 0: dirty 100 (entry 1 s), then clean 100 of file 1. Re-reading file 0 refreshes it:
  // the clean data of file 1 is now the least recently used, the dirty block keeps its entry
  // time, and at cutoff 1 s it is the expired block written back first.
  PageCache cache(10000, lru());
  cache.set_checking(true);
  cache.add_dirty(0, 100, 1.0);
  cache.add_clean(1, 100, 1.5);
  cache.reaccess(0, 100, 2.0);
  CHECK(cache.list(ListKind::Inactive).blocks().begin()->file == 1);
  const PageCache::Flushed taken = cache.flush_expired_block(1.0);
  CHECK(taken.file == 0);
  CHECK(taken.bytes == 100);
  CHECK(cache.list(ListKind::Active).bytes() == 0);
}
