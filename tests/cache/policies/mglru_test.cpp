// The mglru policy (the kernel's multi-generation LRU): reads count references in place, reclaim
// sorts the oldest generation (protected and dirty data to the next one, clean data evicted with
// a shadow), refaulting working-set data comes back a generation younger, and data whose
// writeback ends with the reclaim mark is the next evicted. page_cache_ranges_random_test checks
// every rule byte by byte against a reference; these show each one on its own.
#include "cache/page_cache.hpp"

#include <catch2/catch.hpp>

#include <vector>

using namespace pagecache;
using namespace pagecache::cache;

namespace {

CacheSettings mglru_settings() {
  CacheSettings s = CacheSettings::kernel();
  s.policy = "mglru";
  return s;
}

// The files and policy bits (refs | 8 for the working set | 16 for reclaim) of a list, front first.
std::vector<std::pair<FileId, int>> order(const PageCache& cache, ListKind kind) {
  std::vector<std::pair<FileId, int>> blocks;
  for (const Block& b : cache.list(kind).blocks()) blocks.emplace_back(b.file, b.policy_bits);
  return blocks;
}

}  // namespace

TEST_CASE("mglru: a read counts a reference and moves nothing; the fifth makes the working set", "[policy][mglru]") {
  PageCache cache(10000, mglru_settings());
  cache.set_checking(true);
  CHECK(cache.policy().name() == "mglru");
  cache.add_read(0, 100, 0.0);  // a demand read: its first reference
  cache.add_read(1, 100, 0.0);
  for (int n = 0; n < 3; ++n) cache.reaccess(0, 100, 1.0);
  CHECK(order(cache, ListKind::Inactive) == std::vector<std::pair<FileId, int>>{{0, 4}, {1, 1}});
  cache.reaccess(0, 100, 2.0);
  CHECK(order(cache, ListKind::Inactive) == std::vector<std::pair<FileId, int>>{{0, 4 | 8}, {1, 1}});
  CHECK(cache.list(ListKind::Active).bytes() == 0);
  // Every reference counted and the working-set mark: moved on (lazily promoted), references
  // cleared; file 1 is evicted.
  CHECK(cache.evict(100, kNoFile) == 100);
  CHECK(cache.file(1).cached() == 0);
  CHECK(order(cache, ListKind::Active) == std::vector<std::pair<FileId, int>>{{0, 8}});
}

TEST_CASE("mglru: working-set data evicted and read again comes back in the next generation; other data in the oldest",
          "[policy][mglru]") {
  PageCache cache(10000, mglru_settings());
  cache.set_checking(true);
  cache.add_read(0, 100, 0.0);
  cache.add_read(1, 100, 0.0);
  for (int n = 0; n < 4; ++n) cache.reaccess(0, 100, 1.0);
  // Nothing in the next generation to retire: the oldest is sorted once, file 0 (lazily
  // promoted) moves on, file 1 goes; then the oldest is empty, file 0's generation retires and
  // file 0 goes too, with the working-set mark in its shadow.
  CHECK(cache.evict(200, kNoFile) == 200);
  // Retirement made the shadows of the retired generation old: only evictions after it count.
  cache.add_read(2, 100, 3.0);
  CHECK(cache.evict(100, kNoFile) == 100);
  CHECK(cache.file(2).cached() == 0);
  cache.add_read(2, 100, 4.0);  // a refault of cold data: the oldest generation, as new data
  CHECK(order(cache, ListKind::Inactive) == std::vector<std::pair<FileId, int>>{{2, 1}});
  cache.reaccess(2, 100, 5.0);
  for (int n = 0; n < 3; ++n) cache.reaccess(2, 100, 5.0);  // refs 4 and the working set
  cache.add_read(3, 100, 5.0);
  // File 2 is lazily promoted, file 3 evicted; the oldest generation (file 2's, now) is not retired.
  CHECK(cache.evict(100, kNoFile) == 100);
  CHECK(order(cache, ListKind::Active) == std::vector<std::pair<FileId, int>>{{2, 8}});
  CHECK(cache.evict(100, kNoFile) == 100);  // retired, then file 2 evicted: a working-set shadow
  cache.add_read(2, 100, 6.0);
  CHECK(order(cache, ListKind::Active) == std::vector<std::pair<FileId, int>>{{2, 1 | 8}});
  CHECK(cache.list(ListKind::Inactive).bytes() == 0);
}

TEST_CASE("mglru: dirty data met by reclaim goes to the next generation marked; its writeback's end makes it the next evicted",
          "[policy][mglru]") {
  PageCache cache(10000, mglru_settings());
  cache.set_checking(true);
  cache.add_dirty(0, 100, 0.0);
  cache.add_read(1, 100, 0.0);
  cache.add_read(2, 100, 0.0);
  CHECK(cache.evict(50, kNoFile) == 50);  // file 0 moves on, marked for reclaim; half of file 1 goes
  CHECK(order(cache, ListKind::Active) == std::vector<std::pair<FileId, int>>{{0, 16}});
  std::vector<PageCache::Flushed> taken;
  CHECK(cache.flush(100, kNoFile, taken) == 100);
  for (const PageCache::Flushed& f : taken) cache.end_writeback(f);
  // Clean now, its mark cleared, at the oldest generation's tail: evicted before file 1's rest.
  CHECK(order(cache, ListKind::Inactive) == std::vector<std::pair<FileId, int>>{{0, 0}, {1, 1}, {2, 1}});
  CHECK(cache.evict(100, kNoFile) == 100);
  CHECK(cache.file(0).cached() == 0);
  CHECK(cache.file(1).cached() == 50);
}
