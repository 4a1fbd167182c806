// A chunk read's steps (src/cache/chunk_read.hpp) without a simulator, on small hand-built page
// caches: each expectation is worked out in a comment from Algorithm 2 and the settings.
#include "cache/chunk_read.hpp"

#include <pagecache/cache_settings.hpp>

#include <catch2/catch.hpp>

#include <vector>

namespace pagecache::cache {

TEST_CASE("evict_for_chunk: eviction alone makes room, and counts the file's own data it took", "[chunk_read]") {
  // 1000 bytes: 200 anonymous; file 0 (400 bytes) has 300 cached, the oldest; file 1 has 100:
  // free 400. One chunk of the whole file with a 400-byte buffer: from_disk 100, required 500,
  // evict 100.
  const ReadRequest request{.file = 0, .file_size = 400, .bytes = 400, .anonymous = 400};
  for (const bool kernel : {true, false}) {
    PageCache cache(1000, kernel ? CacheSettings::kernel() : CacheSettings::paper());
    cache.set_checking(true);
    cache.allocate_anonymous(200);
    cache.add_clean(0, 300, 0.0);
    cache.add_clean(1, 100, 1.0);
    ReadPlan needs;
    const std::int64_t from_disk = evict_for_chunk(cache, request, &needs);
    if (kernel) {
      // Reclaim took 100 of the file's own data (the least recently used): from_disk 200,
      // required 600 > free 500: not yet, and the needs say so.
      CHECK(from_disk == -1);
      CHECK(cache.file(0).cached() == 200);
      CHECK(needs.from_disk == 200);
      CHECK(needs.required == 600);
      // A second try evicts the next 100 (file 0's, still the oldest): from_disk 300,
      // required 700 > free 600. Eviction alone chases its own tail.
      CHECK(evict_for_chunk(cache, request) == -1);
      CHECK(cache.file(0).cached() == 100);
    } else {
      // The paper spares the file being read: file 1 goes, 100 from the device.
      CHECK(from_disk == 100);
      CHECK(cache.file(1).cached() == 0);
      CHECK(needs.from_disk == 100);
      CHECK(needs.room.fits);
    }
  }
}

TEST_CASE("evict_for_chunk: when dirty data must be written back first, nothing is evicted", "[chunk_read]") {
  // 1000 bytes: 200 anonymous, file 1 clean (100) then dirty (400): free 300. Kernel: a
  // 300-byte chunk of an uncached file with its buffer needs 600; evictable = clean inactive
  // = 100, so flush 600 - 300 - 100 = 200 > 0: -1, and the clean 100 stays.
  PageCache cache(1000, CacheSettings::kernel());
  cache.set_checking(true);
  cache.allocate_anonymous(200);
  cache.add_clean(1, 100, 0.0);
  cache.add_dirty(1, 400, 1.0);
  ReadPlan needs;
  CHECK(evict_for_chunk(cache, {.file = 0, .file_size = 300, .bytes = 300, .anonymous = 300}, &needs) == -1);
  CHECK(cache.file(1).cached() == 500);
  CHECK(needs.required == 600);
  CHECK(needs.room.flush == 200);
}

TEST_CASE("evict_to_fit evicts what is not free and says whether the bytes fit", "[chunk_read]") {
  // 1000 bytes, file 0 clean 600, file 1 clean 300: free 100. 350 fit after evicting 250 of
  // file 0 (the oldest); sparing file 0, 250 of file 1 go. With 200 anonymous and 800 clean,
  // 900 cannot fit: all 800 go, 100 short.
  for (const FileId spared : {kNoFile, FileId{0}}) {
    PageCache cache(1000, CacheSettings::kernel());
    cache.set_checking(true);
    cache.add_clean(0, 600, 0.0);
    cache.add_clean(1, 300, 1.0);
    CHECK(evict_to_fit(cache, 350, spared));
    CHECK(cache.free() == 350);
    CHECK(cache.file(spared == kNoFile ? 0 : 1).cached() == (spared == kNoFile ? 350 : 50));
  }
  PageCache full(1000, CacheSettings::kernel());
  full.set_checking(true);
  full.allocate_anonymous(200);
  full.add_clean(0, 800, 0.0);
  CHECK_FALSE(evict_to_fit(full, 900, kNoFile));
  CHECK(full.free() == 800);
}

TEST_CASE("start_chunk: new data, the re-access, the buffer, all before any transfer", "[chunk_read]") {
  // File 0 (500 bytes) has 300 cached. A 400-byte chunk with 100 from the device: 100 new
  // clean bytes, 300 re-accessed (kernel: the data read from the device was its first touch,
  // so the re-read activates the 300), 400 anonymous. Free: 1000 - 400 - 400 = 200. Then the
  // lists are balanced (active <= 2 x inactive): the least x with 300 - x <= 2 (100 + x) is
  // 34 bytes back to the inactive list, 266 stay active.
  PageCache cache(1000, CacheSettings::kernel());
  cache.set_checking(true);
  cache.add_read(0, 300, 0.0);
  const ReadRequest request{.file = 0, .file_size = 500, .bytes = 400, .anonymous = 400};
  start_chunk(cache, request, 100, {}, kRootGroup, 1.0);
  CHECK(cache.file(0).cached() == 400);
  CHECK(cache.file(0).in(ListKind::Active) == 266);
  CHECK(cache.memory().anonymous == 400);
  CHECK(cache.free() == 200);
  // A server's chunk has no buffer of its own: nothing anonymous is taken.
  start_chunk(cache, {.file = 1, .file_size = 100, .bytes = 100, .anonymous = 0}, 100, {}, kRootGroup, 2.0);
  CHECK(cache.memory().anonymous == 400);
  CHECK(cache.file(1).cached() == 100);
}

}  // namespace pagecache::cache
