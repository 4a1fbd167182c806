// BlockPool and BlockList, the storage under PageCache's lists: random operations on a pool
// and two lists threaded through the same blocks, checked after every step against
// std::list references; ids and contents stay while the pool grows (and moves its array).
#include "cache/block_list.hpp"
#include "cache/block_pool.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <list>
#include <random>
#include <vector>

using namespace pagecache::cache;

namespace {

using LruLinks = BlockList<&Block::lru, true>;
using FileLinks = BlockList<&Block::in_file, false>;

template <class List>
std::vector<BlockId> forward(const BlockPool& pool, const List& list) {
  std::vector<BlockId> ids;
  for (BlockId id = list.front(); id != kNoBlock; id = List::next(pool, id)) ids.push_back(id);
  return ids;
}

template <class List>
std::vector<BlockId> backward(const BlockPool& pool, const List& list) {
  std::vector<BlockId> ids;
  for (BlockId id = list.back(); id != kNoBlock; id = List::prev(pool, id)) ids.push_back(id);
  std::reverse(ids.begin(), ids.end());
  return ids;
}

template <class List>
void check(const BlockPool& pool, const List& list, const std::list<BlockId>& expected) {
  const std::vector<BlockId> want(expected.begin(), expected.end());
  REQUIRE(forward(pool, list) == want);
  REQUIRE(backward(pool, list) == want);
  REQUIRE(list.empty() == want.empty());
}

}  // namespace

TEST_CASE("a block pool hands out blocks as new, recycles the last given back, and keeps them as it grows", "[block]") {
  BlockPool pool;
  std::vector<BlockId> ids;
  for (std::int64_t i = 0; i < 70000; ++i) {  // more than one chunk
    const BlockId id = pool.take();
    REQUIRE(pool[id].size == 0);
    REQUIRE(pool[id].lru.prev == kNoBlock);
    pool[id].size = i + 1;
    pool[id].entry_time = static_cast<double>(i);
    ids.push_back(id);
  }
  REQUIRE(pool.in_use() == 70000);
  for (std::int64_t i = 0; i < 70000; ++i) {
    REQUIRE(pool[ids[static_cast<std::size_t>(i)]].size == i + 1);  // what was written is still there
    REQUIRE(reinterpret_cast<std::uintptr_t>(&pool[ids[static_cast<std::size_t>(i)]]) % 64 == 0);  // one cache line each
  }
  pool.give_back(ids[10]);
  pool.give_back(ids[20]);
  REQUIRE(pool.in_use() == 69998);
  const BlockId again = pool.take();
  CHECK(again == ids[20]);           // last in, first out: likely still in cache
  CHECK(pool[again].size == 0);      // and reset
  CHECK(pool[again].entry_time == 0.0);
  CHECK(pool.take() == ids[10]);
  CHECK(pool.in_use() == 70000);
}

TEST_CASE("block lists agree with std::list under random links and unlinks", "[block]") {
  std::mt19937_64 rng(GENERATE(1, 2, 3));
  BlockPool pool;
  LruLinks lru;
  FileLinks file;  // a second list through the same blocks, uncounted
  std::list<BlockId> lru_ref;
  std::list<BlockId> file_ref;
  std::vector<BlockId> unlinked;
  auto pick = [&](const std::list<BlockId>& from) {
    auto it = from.begin();
    std::advance(it, static_cast<long>(rng() % from.size()));
    return it;
  };
  for (int step = 0; step < 20000; ++step) {
    const unsigned op = static_cast<unsigned>(rng() % 6);
    if (op < 3 || lru_ref.empty()) {
      // Link a block (a fresh one, or one unlinked before) into the LRU list somewhere, and at
      // the end of the file list.
      BlockId id;
      if (!unlinked.empty() && rng() % 2 == 0) {
        id = unlinked.back();
        unlinked.pop_back();
      } else {
        id = pool.take();
      }
      if (lru_ref.empty() || op == 0) {
        lru.push_back(pool, id);
        lru_ref.push_back(id);
      } else if (op == 1) {
        lru.push_front(pool, id);
        lru_ref.push_front(id);
      } else {
        const auto at = pick(lru_ref);
        if (rng() % 2 == 0) {
          lru.insert_after(pool, *at, id);
          lru_ref.insert(std::next(at), id);
        } else {
          lru.insert_before(pool, *at, id);
          lru_ref.insert(at, id);
        }
      }
      file.push_back(pool, id);
      file_ref.push_back(id);
    } else {
      // Unlink a block from both lists; sometimes give it back to the pool.
      const auto at = pick(lru_ref);
      const BlockId id = *at;
      lru.erase(pool, id);
      lru_ref.erase(at);
      file.erase(pool, id);
      file_ref.remove(id);
      REQUIRE(pool[id].lru.prev == kNoBlock);
      REQUIRE(pool[id].lru.next == kNoBlock);
      REQUIRE(pool[id].in_file.next == kNoBlock);
      if (rng() % 2 == 0) pool.give_back(id);
      else unlinked.push_back(id);
    }
    REQUIRE(lru.size() == lru_ref.size());
    if (step % 97 == 0 || lru_ref.size() < 8) {
      check(pool, lru, lru_ref);
      check(pool, file, file_ref);
    }
  }
  check(pool, lru, lru_ref);
  check(pool, file, file_ref);
}

TEST_CASE("link_in_order puts a block into a sub-list at its place in the list", "[block]") {
  BlockPool pool;
  LruLinks list;
  BlockList<&Block::by_state, true> dirty;  // the sub-list of dirty blocks
  std::vector<BlockId> ids;
  for (int i = 0; i < 8; ++i) {
    ids.push_back(pool.take());
    list.push_back(pool, ids.back());
  }
  const auto is_dirty = [](const Block& b) { return b.state == BlockState::Dirty; };
  // Blocks become dirty in the order 5, 1, 7, 3, 0: the sub-list keeps the list's order.
  for (const int i : {5, 1, 7, 3, 0}) {
    pool[ids[static_cast<std::size_t>(i)]].state = BlockState::Dirty;
    link_in_order(pool, list, dirty, ids[static_cast<std::size_t>(i)], is_dirty);
  }
  CHECK(forward(pool, dirty) == std::vector<BlockId>{ids[0], ids[1], ids[3], ids[5], ids[7]});
  CHECK(backward(pool, dirty) == std::vector<BlockId>{ids[0], ids[1], ids[3], ids[5], ids[7]});
  CHECK(dirty.size() == 5);
}
