// MemoryGroups on its own: limits refused, the root's charges from the host's, a file moved to a
// group, the headrooms, and its check catching charges that disagree with the files'.
#include "cache/memory_groups.hpp"

#include <pagecache/error.hpp>

#include <catch2/catch.hpp>

#include <cstdint>
#include <limits>
#include <vector>

using namespace pagecache;
using namespace pagecache::cache;

TEST_CASE("a memory group's limits are checked when it is added", "[groups]") {
  MemoryGroups groups;
  CHECK(groups.empty());
  CHECK(groups.of(5) == kRootGroup);
  CHECK(groups.headroom(kRootGroup) == std::numeric_limits<std::int64_t>::max());
  CHECK_THROWS_AS(groups.add(0, 0, {}), ConfigError);
  CHECK_THROWS_AS(groups.add(100, 101, {}), ConfigError);
  CHECK_THROWS_AS(groups.add(100, -1, {}), ConfigError);
  CHECK(groups.empty());
}

TEST_CASE("the root group starts with what the host holds; a file moved takes its charges along", "[groups]") {
  MemoryGroups groups;
  const GroupId g = groups.add(1000, 600, {.anonymous = 50, .cached = 300, .dirty_and_writeback = 40});
  CHECK(g == 1);
  CHECK(groups.size() == 2);
  CHECK(groups.usage(kRootGroup) == 350);
  CHECK(groups.dirty_and_writeback(kRootGroup) == 40);
  groups.move(7, g, 200, 30);  // file 7: 200 bytes cached, 30 of them dirty
  CHECK(groups.of(7) == g);
  CHECK(groups.cached(kRootGroup) == 100);
  CHECK(groups.cached(g) == 200);
  CHECK(groups.dirty_and_writeback(g) == 30);
  // New data of the file is the group's; application memory is charged by group.
  groups.charge(7, 100);
  groups.charge_dirty(7, 100);
  groups.charge_anonymous(g, 50);
  CHECK(groups.usage(g) == 350);
  CHECK(groups.headroom(g) == 650);
  CHECK(groups.ceiling_headroom(g) == 250);  // memory.high (600) is the lower ceiling
  CHECK(groups.over_high(g, 300) == 50);
  CHECK(groups.over_high(kRootGroup, 1'000'000) == 0);
  CHECK(groups.max(g) == 1000);
  groups.check({100, 300}, {10, 130}, 100);
}

TEST_CASE("MemoryGroups' check catches charges that are not the files'", "[groups]") {
  MemoryGroups groups;
  const GroupId g = groups.add(1000, 0, {.anonymous = 0, .cached = 100, .dirty_and_writeback = 0});
  groups.move(1, g, 100, 0);
  CHECK_NOTHROW(groups.check({0, 100}, {0, 0}, 0));
  CHECK_THROWS_AS(groups.check({0, 90}, {0, 0}, 0), InvariantError);   // the files hold less
  CHECK_THROWS_AS(groups.check({0, 100}, {0, 5}, 0), InvariantError);  // dirty data not charged
  CHECK_THROWS_AS(groups.check({0, 100}, {0, 0}, 8), InvariantError);  // the host's anonymous memory differs
  // A file in the reclaim heap of a group it is not charged to.
  groups.reclaimable(ListKind::Inactive).lower(g, 2, 17);
  CHECK_THROWS_AS(groups.check({0, 100}, {0, 0}, 0), InvariantError);
}
