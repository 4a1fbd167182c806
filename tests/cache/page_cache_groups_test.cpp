// Memory groups in the page cache (cgroup v2 memory.max, first cut): charges, and reclaim and
// writeback confined to a group. Each expectation is derived in a comment.
#include "cache/page_cache.hpp"

#include <pagecache/error.hpp>

#include <catch2/catch.hpp>

#include <vector>

using namespace pagecache;
using namespace pagecache::cache;

namespace {
constexpr auto I = ListKind::Inactive;
constexpr auto A = ListKind::Active;
}  // namespace

TEST_CASE("a group at its limit reclaims its own data while the host has free memory", "[page_cache][groups]") {
  // mm/memcontrol.c try_charge: over memory.max, the group reclaims from its own lists
  // (try_to_free_mem_cgroup_pages), whatever the host's free memory. 10,000 bytes; group 1
  // may hold 300. File 0 (not in a group, 500 clean) is the oldest data; file 1, charged to
  // the group, 200 clean. The group wants 200 bytes of application memory: room 300 - 200 =
  // 100, so 100 must go, and they are the group's: half of file 1, not the older file 0.
  for (const bool kernel : {true, false}) {
    PageCache cache(10'000, kernel ? CacheSettings::kernel() : CacheSettings::paper());
    cache.set_checking(true);
    const GroupId group = cache.add_group(300);
    CHECK(group == 1);
    cache.add_clean(0, 500, 0.0);
    cache.charge_file(1, group);
    cache.add_clean(1, 200, 1.0);
    CHECK(group_usage(cache, group) == 200);
    CHECK(group_room(cache, group) == 100);
    CHECK(group_usage(cache, kRootGroup) == 500);
    CHECK(cache.evict(200 - group_room(cache, group), kNoFile, group) == 100);
    CHECK(cache.file(0).cached() == 500);
    CHECK(cache.file(1).cached() == 100);
    cache.allocate_anonymous(200, group);
    CHECK(group_usage(cache, group) == 300);
    CHECK(group_room(cache, group) == 0);
    // Past the limit: refused, the group named.
    CHECK_THROWS_WITH(cache.allocate_anonymous(1, group), Catch::Contains("memory group 1 over its limit"));
    // Not confined: the same eviction takes the oldest data, file 0's.
    CHECK(cache.evict(100, kNoFile) == 100);
    CHECK(cache.file(0).cached() == 400);
    cache.release_anonymous(200, group);
    CHECK(group_usage(cache, group) == 100);
  }
}

TEST_CASE("a file is charged to the first group that caches it", "[page_cache][groups]") {
  // Data cached before any charge is the root group's; charging the file moves it to the
  // group, and a second group's charge changes nothing (pcsim charges whole files).
  PageCache cache(10'000, CacheSettings::kernel());
  cache.set_checking(true);
  cache.add_clean(0, 100, 0.0);
  const GroupId g1 = cache.add_group(1000);
  const GroupId g2 = cache.add_group(1000);
  CHECK(group_usage(cache, kRootGroup) == 100);
  cache.charge_file(0, g1);
  CHECK(cache.groups().of(0) == g1);
  CHECK(group_usage(cache, kRootGroup) == 0);
  CHECK(cache.groups().cached(g1) == 100);
  cache.charge_file(0, g2);
  CHECK(cache.groups().of(0) == g1);
  cache.add_read(0, 50, 1.0);  // more data of the file: its group's
  CHECK(cache.groups().cached(g1) == 150);
  CHECK(cache.groups().cached(g2) == 0);
  cache.drop_file(0);
  CHECK(cache.groups().cached(g1) == 0);
}

TEST_CASE("a group's writeback and active-list aging take only its data", "[page_cache][groups]") {
  // Dirty: file 0 (root, 100, oldest), file 1 (group, 100). A flush of 50 for the group takes
  // 50 of file 1. Kernel reclaim of a group with no clean inactive data ages the group's
  // active data only: file 2 (root) re-read twice, then file 3 (group) likewise, both active;
  // evicting 60 for the group deactivates and takes 60 of file 3, file 2 stays active.
  PageCache cache(10'000, CacheSettings::kernel());
  cache.set_checking(true);
  const GroupId group = cache.add_group(5000);
  cache.charge_file(1, group);
  cache.charge_file(3, group);
  cache.add_dirty(0, 100, 0.0);
  cache.add_dirty(1, 100, 1.0);
  std::vector<PageCache::Flushed> taken;
  CHECK(cache.flush(50, kNoFile, taken, group) == 50);
  REQUIRE(taken.size() == 1);
  CHECK(taken[0].file == 1);
  for (const auto& t : taken) cache.end_writeback(t);
  CHECK(cache.file(0).dirty == 100);
  cache.add_clean(9, 1000, 2.0);  // root data, keeps active <= 2 x inactive
  for (const FileId f : {FileId{2}, FileId{3}}) {
    cache.add_read(f, 100, 3.0);
    cache.reaccess(f, 100, 4.0);
  }
  REQUIRE(cache.file(2).in(A) == 100);
  REQUIRE(cache.file(3).in(A) == 100);
  // The group's clean inactive data: 50 of file 1 (written back above). It goes first.
  CHECK(cache.evict(110, kNoFile, group) == 110);
  CHECK(cache.file(1).cached() == 50);  // its dirty half stays
  CHECK(cache.file(3).cached() == 40);
  CHECK(cache.file(3).in(I) == 40);  // deactivated with the part evicted
  CHECK(cache.file(2).in(A) == 100);
  CHECK(cache.file(9).cached() == 1000);
}
