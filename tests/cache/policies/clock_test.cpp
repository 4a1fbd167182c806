// The clock policy (CLOCK, second chance): a hit sets a bit and moves nothing; reclaim passes
// over referenced data once, clearing its bit, and evicts the first unreferenced clean data.
#include "cache/page_cache.hpp"

#include <catch2/catch.hpp>

#include <vector>

using namespace pagecache;
using namespace pagecache::cache;

namespace {

CacheSettings clock_settings() {
  CacheSettings s = CacheSettings::kernel();
  s.policy = "clock";
  return s;
}

// The files of the list's blocks, front first, with their referenced bits.
std::vector<std::pair<FileId, bool>> order(const PageCache& cache) {
  std::vector<std::pair<FileId, bool>> files;
  for (const Block& b : cache.list(ListKind::Inactive).blocks()) files.emplace_back(b.file, b.referenced);
  return files;
}

}  // namespace

TEST_CASE("clock: a hit sets the bit and moves nothing; reclaim gives referenced data a second chance", "[policy][clock]") {
  // Files 0, 1, 2, 3 of 100 bytes each, added clean (bits clear); files 0 and 2 re-read.
  PageCache cache(10000, clock_settings());
  cache.set_checking(true);
  CHECK(cache.policy().name() == "clock");
  for (FileId f = 0; f < 4; ++f) cache.add_clean(f, 100, 0.0);
  cache.reaccess(0, 100, 1.0);
  cache.reaccess(2, 100, 1.0);
  CHECK(order(cache) == std::vector<std::pair<FileId, bool>>{{0, true}, {1, false}, {2, true}, {3, false}});
  CHECK(cache.list(ListKind::Active).bytes() == 0);
  // 150 bytes: the hand clears file 0's bit (to the back), evicts file 1, clears file 2's
  // bit, evicts half of file 3 (first in, first out would have taken file 0 and half of 1).
  CHECK(cache.evict(150, kNoFile) == 150);
  CHECK(cache.file(1).cached() == 0);
  CHECK(cache.file(3).cached() == 50);
  CHECK(order(cache) == std::vector<std::pair<FileId, bool>>{{3, false}, {0, false}, {2, false}});
  // A second pass: every bit is clear now, so the hand evicts in order.
  CHECK(cache.evict(100, kNoFile) == 100);
  CHECK(cache.file(3).cached() == 0);
  CHECK(cache.file(0).cached() == 50);
}

TEST_CASE("clock: data read from a device starts referenced; when every bit is set the hand goes round once", "[policy][clock]") {
  PageCache cache(10000, clock_settings());
  cache.set_checking(true);
  cache.add_read(0, 100, 0.0);
  cache.add_read(1, 100, 0.0);
  CHECK(order(cache) == std::vector<std::pair<FileId, bool>>{{0, true}, {1, true}});
  // All referenced: both lose their bits and go round; then file 0 is the first taken.
  CHECK(cache.evict(60, kNoFile) == 60);
  CHECK(cache.file(0).cached() == 40);
  CHECK(cache.file(1).cached() == 100);
}

TEST_CASE("clock: dirty data and the excluded file are passed over with their bits", "[policy][clock]") {
  PageCache cache(10000, clock_settings());
  cache.set_checking(true);
  cache.add_dirty(0, 100, 0.0);
  cache.add_read(1, 100, 0.0);
  cache.add_clean(2, 100, 0.0);
  cache.reaccess(0, 100, 1.0);  // a dirty block re-read: its bit set, still dirty, in place
  CHECK(cache.evict(300, 2) == 100);  // only file 1 may go (after its second chance)
  CHECK(cache.file(0).cached() == 100);
  CHECK(cache.file(1).cached() == 0);
  CHECK(cache.file(2).cached() == 100);
  CHECK(order(cache) == std::vector<std::pair<FileId, bool>>{{0, true}, {2, false}});
  CHECK(cache.policy().evictable(cache) == 100);
}

TEST_CASE("clock: a memory group's reclaim moves only its own data's hand; a node's reclaim its own", "[policy][clock][groups][numa]") {
  PageCache cache(10000, clock_settings());
  cache.set_checking(true);
  const GroupId g = cache.add_group(5000);
  cache.add_read(0, 100, 0.0);  // the root's, referenced
  cache.add_read(1, 100, 0.0);  // the group's, referenced
  cache.add_clean(2, 100, 0.0);  // the group's
  cache.charge_file(1, g);
  cache.charge_file(2, g);
  CHECK(cache.evict(150, kNoFile, g) == 150);
  CHECK(cache.file(0).cached() == 100);
  CHECK(cache.file(2).cached() == 0);
  CHECK(cache.file(1).cached() == 50);
  CHECK(order(cache) == std::vector<std::pair<FileId, bool>>{{0, true}, {1, false}});

  // Two nodes: file 3 on node 0, file 4 on node 1 (its thread's), each reclaimed by its own
  // node's share.
  PageCache two(1000, clock_settings(), {.nodes = 2});
  two.set_checking(true);
  two.add_read(3, 400, 0.0);
  two.touch_from(1);
  two.add_clean(4, 400, 0.0);
  CHECK(two.evict(200, kNoFile) == 200);
  CHECK(two.file(3).cached() == 300);
  CHECK(two.file(4).cached() == 300);
}
