// Randomised check of PageCache against a deliberately simple reference model: two plain
// vectors of blocks, every operation written as the obvious loop. 10^5+ random operations
// (reads, writes, flushes with writebacks left in flight and ended out of order, expiry
// flushes, often several under one cutoff as the flusher's tick makes them, evictions, re-accesses, application memory, reservations of copies in flight,
// writes of files starting and ending, which eviction spares with protect_files_being_written;
// with memory groups, files charged to them and evictions and flushes of one group)
// run on both, and after every step the lists (block by block, in order), the per-file
// cached and dirty bytes and the memory totals must agree exactly, with every invariant
// checked by PageCache itself.
#include "cache/page_cache.hpp"

#include <pagecache/error.hpp>

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

using namespace pagecache;
using namespace pagecache::cache;

namespace {

constexpr int kFiles = 6;

struct RefBlock {
  FileId file;
  std::int64_t size;
  BlockState state;
  double entry;
  std::uint64_t token;  // writeback in progress
  bool referenced = false;
};

class Reference {
 public:
  Reference(std::int64_t total, const CacheSettings& s)
      : total_(total),
        s_{s.get("balance_after_every_change"), s.get("two_touch_activation"), s.get("flush_splits_in_place"),
           s.get("reclaim_inactive_only"), s.get("protect_files_being_written")} {}

  std::vector<RefBlock> inactive, active;
  std::int64_t anonymous = 0, reserved = 0;
  std::uint64_t next_token = 1;
  std::vector<int> writers = std::vector<int>(kFiles, 0);  // writes in progress, per file
  std::vector<GroupId> group = std::vector<GroupId>(kFiles, kRootGroup);  // each file's memory group
  // The walks' target: kAnyGroup, or only that group's files.
  GroupId target = kAnyGroup;
  bool in_target(const RefBlock& b) const { return target == kAnyGroup || group[b.file] == target; }
  std::int64_t group_cached(GroupId g) const {
    std::int64_t n = 0;
    for (FileId f = 0; f < kFiles; ++f)
      if (group[f] == g) n += cached(f);
    return n;
  }
  std::int64_t group_unclean(GroupId g) const {
    std::int64_t n = 0;
    for (const auto* list : {&inactive, &active})
      for (const auto& b : *list)
        if (group[b.file] == g && b.state != BlockState::Clean) n += b.size;
    return n;
  }

  static std::int64_t sum(const std::vector<RefBlock>& list) {
    std::int64_t n = 0;
    for (const auto& b : list) n += b.size;
    return n;
  }
  static std::int64_t sum(const std::vector<RefBlock>& list, BlockState st) {
    std::int64_t n = 0;
    for (const auto& b : list)
      if (b.state == st) n += b.size;
    return n;
  }
  std::int64_t cached() const { return sum(inactive) + sum(active); }
  std::int64_t free() const { return total_ - anonymous - reserved - cached(); }
  std::int64_t dirty() const { return sum(inactive, BlockState::Dirty) + sum(active, BlockState::Dirty); }
  std::int64_t cached(FileId f) const {
    std::int64_t n = 0;
    for (const auto* list : {&inactive, &active})
      for (const auto& b : *list)
        if (b.file == f) n += b.size;
    return n;
  }
  std::int64_t dirty(FileId f) const {
    std::int64_t n = 0;
    for (const auto* list : {&inactive, &active})
      for (const auto& b : *list)
        if (b.file == f && b.state == BlockState::Dirty) n += b.size;
    return n;
  }

  void settle() {
    if (s_.balance_after_every_change) balance();
  }

  // New clean data right behind a clean block of the same file (same mark) extends it.
  static void push_new(std::vector<RefBlock>& list, const RefBlock& b) {
    if (b.state == BlockState::Clean && !list.empty() && list.back().file == b.file && list.back().state == BlockState::Clean &&
        list.back().referenced == b.referenced) {
      list.back().size += b.size;
    } else {
      list.push_back(b);
    }
  }

  void add(FileId f, std::int64_t bytes, BlockState st, double now, bool referenced = false) {
    if (bytes == 0) return;
    push_new(inactive, {f, bytes, st, now, 0, referenced});
    settle();
  }

  void balance() {
    const std::int64_t excess = sum(active) - 2 * sum(inactive);
    if (excess <= 0) return;
    std::int64_t move = (excess + 2) / 3;
    while (move > 0) {
      RefBlock b = active.front();
      if (b.size > move) {
        active.front().size -= move;
        b.size = move;
      } else {
        active.erase(active.begin());
      }
      move -= b.size;
      b.referenced = false;
      inactive.push_back(b);
    }
  }

  void reaccess(FileId f, std::int64_t bytes, double now) {
    std::int64_t left = bytes;
    std::int64_t merged = 0;
    // Inactive blocks of f in order; with two-touch activation an unreferenced one is only
    // marked (the part read, split off in place).
    for (std::size_t i = 0; i < inactive.size() && left > 0;) {
      if (inactive[i].file != f) {
        ++i;
        continue;
      }
      RefBlock b = inactive[i];
      const bool partial = b.size > left;
      if (partial) b.size = left;
      left -= b.size;
      if (s_.two_touch_activation && !b.referenced) {
        b.referenced = true;
        if (partial) {
          inactive[i].size -= b.size;
          inactive.insert(inactive.begin() + static_cast<std::ptrdiff_t>(i), b);
        } else {
          inactive[i] = b;
        }
        i += partial ? 2 : 1;
        continue;
      }
      if (partial) {
        inactive[i].size -= b.size;
        ++i;
      } else {
        inactive.erase(inactive.begin() + static_cast<std::ptrdiff_t>(i));
      }
      if (b.state == BlockState::Clean) {
        merged += b.size;
      } else {
        b.referenced = false;
        active.push_back(b);
      }
    }
    // Active blocks of f that were there before this call, in order.
    std::size_t originals = active.size();
    for (std::size_t i = 0; i < originals && left > 0;) {
      if (active[i].file != f) {
        ++i;
        continue;
      }
      RefBlock b = active[i];
      b.referenced = false;
      if (b.size > left) {
        active[i].size -= left;
        b.size = left;
        left -= b.size;
        if (b.state == BlockState::Clean) merged += b.size;
        else active.push_back(b);
        break;
      }
      active.erase(active.begin() + static_cast<std::ptrdiff_t>(i));
      --originals;
      left -= b.size;
      if (b.state == BlockState::Clean) merged += b.size;
      else active.push_back(b);
    }
    REQUIRE(left == 0);
    if (merged > 0) push_new(active, {f, merged, BlockState::Clean, now, 0});
    balance();
    settle();
  }

  std::vector<PageCache::Flushed> flush(std::int64_t amount, FileId excluded, GroupId g = kAnyGroup) {
    target = g;
    std::vector<PageCache::Flushed> out;
    std::int64_t flushed = 0;
    std::vector<RefBlock> moved;  // flushed heads of split blocks (paper: to the inactive tail)
    for (auto* list : {&inactive, &active}) {
      for (std::size_t i = 0; i < list->size() && flushed < amount; ++i) {
        RefBlock& b = (*list)[i];
        if (b.state != BlockState::Dirty || b.file == excluded || !in_target(b)) continue;
        const bool partial = b.size > amount - flushed;
        RefBlock head = b;
        if (partial) {
          head.size = amount - flushed;
          b.size -= head.size;
        }
        head.state = BlockState::Writeback;
        flushed += head.size;
        // A write per run of one file's blocks.
        if (!out.empty() && out.back().file == head.file) out.back().bytes += head.size;
        else out.push_back({head.file, head.size, next_token++});
        head.token = out.back().token;
        if (!partial) {
          b = head;
        } else if (s_.flush_splits_in_place) {
          list->insert(list->begin() + static_cast<std::ptrdiff_t>(i), head);
          ++i;
        } else {
          moved.push_back(head);
        }
      }
    }
    for (const auto& b : moved) inactive.push_back(b);
    target = kAnyGroup;
    settle();
    return out;
  }

  PageCache::Flushed flush_expired(double cutoff) {
    for (auto* list : {&inactive, &active}) {
      for (auto& b : *list) {
        if (b.state == BlockState::Dirty && b.entry <= cutoff) {
          b.state = BlockState::Writeback;
          b.token = next_token++;
          settle();
          return {b.file, b.size, b.token};
        }
      }
    }
    return {kNoFile, 0};
  }

  void end_writeback(std::uint64_t token) {
    for (auto* list : {&inactive, &active})
      for (auto& b : *list)
        if (b.token == token) {
          b.token = 0;
          b.state = BlockState::Clean;
        }
    settle();
  }

  // Two passes with protect_files_being_written: the first spares the files being written
  // too, the second (if the first freed too little) only `excluded`.
  std::int64_t evict(std::int64_t amount, FileId excluded, GroupId g = kAnyGroup) {
    target = g;
    std::int64_t evicted = 0;
    auto pass = [&](bool spare_written) {
      auto spared = [&](const RefBlock& b) { return b.file == excluded || (spare_written && writers[b.file] > 0) || !in_target(b); };
      for (auto* list : {&inactive, &active}) {
        if (list == &active && s_.reclaim_inactive_only) break;
        for (std::size_t i = 0; i < list->size() && evicted < amount;) {
          RefBlock& b = (*list)[i];
          if (b.state != BlockState::Clean || spared(b)) {
            ++i;
            continue;
          }
          if (b.size > amount - evicted) {
            b.size -= amount - evicted;
            evicted = amount;
          } else {
            evicted += b.size;
            list->erase(list->begin() + static_cast<std::ptrdiff_t>(i));
          }
        }
      }
      if (s_.reclaim_inactive_only) {
        // Aging: the oldest active block (of the target) goes to the inactive tail, and is
        // reclaimed if clean.
        for (;;) {
          const auto oldest = std::find_if(active.begin(), active.end(), [&](const RefBlock& b) { return in_target(b); });
          if (evicted >= amount || oldest == active.end()) break;
          RefBlock b = *oldest;
          active.erase(oldest);
          b.referenced = false;
          if (b.state == BlockState::Clean && !spared(b)) {
            if (b.size > amount - evicted) {
              b.size -= amount - evicted;
              evicted = amount;
              inactive.push_back(b);
            } else {
              evicted += b.size;
            }
          } else {
            inactive.push_back(b);
          }
        }
      }
    };
    pass(s_.protect_files_being_written);
    if (evicted < amount && s_.protect_files_being_written) pass(false);
    target = kAnyGroup;
    settle();
    return evicted;
  }

 private:
  std::int64_t total_;
  // The switches the reference follows, read once.
  struct {
    bool balance_after_every_change, two_touch_activation, flush_splits_in_place, reclaim_inactive_only, protect_files_being_written;
  } s_;
};

void compare(const PageCache& cache, const Reference& ref, std::uint64_t step) {
  INFO("step " << step);
  for (ListKind kind : {ListKind::Inactive, ListKind::Active}) {
    const auto& expected = kind == ListKind::Inactive ? ref.inactive : ref.active;
    const auto& actual = cache.list(kind).blocks();
    REQUIRE(actual.size() == expected.size());
    auto it = actual.begin();
    for (const RefBlock& e : expected) {
      REQUIRE(it->file == e.file);
      REQUIRE(it->size == e.size);
      REQUIRE(it->state == e.state);
      REQUIRE(it->referenced == e.referenced);
      ++it;
    }
  }
  for (FileId f = 0; f < kFiles; ++f) {
    REQUIRE(cache.file(f).cached() == ref.cached(f));
    REQUIRE(cache.file(f).dirty == ref.dirty(f));
  }
  REQUIRE(cache.free() == ref.free());
  REQUIRE(cache.memory().dirty == ref.dirty());
  REQUIRE(cache.memory().anonymous == ref.anonymous);
  REQUIRE(cache.memory().reserved == ref.reserved);
  for (std::size_t g = 0; g < cache.groups().size(); ++g) {
    const auto group = static_cast<GroupId>(g);
    REQUIRE(cache.groups().cached(group) == ref.group_cached(group));
    REQUIRE(cache.groups().dirty_and_writeback(group) == ref.group_unclean(group));
  }
}

// `groups`: files are charged to two memory groups as the run goes, and evictions and flushes
// target one group or all (limits high enough never to refuse: the I/O controller's business).
void run_random(const CacheSettings& settings, std::uint64_t seed, int steps, bool groups = false) {
  constexpr std::int64_t kTotal = 3000;
  PageCache cache(kTotal, settings);
  cache.set_checking(true);
  Reference ref(kTotal, settings);
  if (groups) {
    REQUIRE(cache.add_group(kTotal) == 1);
    REQUIRE(cache.add_group(kTotal, kTotal / 2) == 2);
  }
  // The target of an eviction or flush: any group, or (with groups) one of those added.
  auto target = [&](std::int64_t roll) { return groups && roll > 0 ? static_cast<GroupId>(roll) : kAnyGroup; };
  std::vector<std::int64_t> anonymous(groups ? 3 : 1, 0);  // by group
  std::mt19937_64 rng(seed);
  auto pick = [&](std::int64_t lo, std::int64_t hi) { return std::uniform_int_distribution<std::int64_t>(lo, hi)(rng); };
  std::vector<PageCache::Flushed> in_flight;   // writebacks not yet ended
  std::vector<std::pair<FileId, std::int64_t>> copies;  // reservations not yet committed
  double now = 0.0;
  double cutoff = 0.0;

  for (int step = 0; step < steps; ++step) {
    now += static_cast<double>(pick(0, 3));
    const auto file = static_cast<FileId>(pick(0, kFiles - 1));
    const auto op = pick(0, groups ? 14 : 13);
    switch (op) {
      case 0:
      case 1: {  // new data read or written
        const std::int64_t bytes = std::min<std::int64_t>(pick(1, 120), cache.free());
        const BlockState st = op == 0 ? BlockState::Clean : BlockState::Dirty;
        if (st == BlockState::Clean) cache.add_clean(file, bytes, now);
        else cache.add_dirty(file, bytes, now);
        ref.add(file, bytes, st, now);
        break;
      }
      case 2: {  // cache hit
        const std::int64_t bytes = pick(0, cache.file(file).cached());
        cache.reaccess(file, bytes, now);
        ref.reaccess(file, bytes, now);
        break;
      }
      case 3: {  // forced flush, written back later
        const std::int64_t amount = pick(1, 300);
        const FileId excluded = pick(0, 1) ? file : kNoFile;
        const GroupId group = target(pick(0, 2));
        std::vector<PageCache::Flushed> got;
        cache.flush(amount, excluded, got, group);
        const auto want = ref.flush(amount, excluded, group);
        REQUIRE(got.size() == want.size());
        for (std::size_t i = 0; i < got.size(); ++i) {
          REQUIRE(got[i].file == want[i].file);
          REQUIRE(got[i].bytes == want[i].bytes);
          in_flight.push_back(got[i]);
        }
        break;
      }
      case 4: {  // periodic flusher: half the time under the previous cutoff, as within a tick
        if (pick(0, 1)) cutoff = now - static_cast<double>(pick(0, 40));
        const auto got = cache.flush_expired_block(cutoff);
        const auto want = ref.flush_expired(cutoff);
        REQUIRE(got.file == want.file);
        REQUIRE(got.bytes == want.bytes);
        if (got.bytes > 0) in_flight.push_back(got);
        break;
      }
      case 5: {  // a writeback ends (any one: devices finish out of order)
        if (in_flight.empty()) break;
        const auto i = static_cast<std::size_t>(pick(0, static_cast<std::int64_t>(in_flight.size()) - 1));
        const auto done = in_flight[i];
        in_flight.erase(in_flight.begin() + static_cast<std::ptrdiff_t>(i));
        // Each part of a flush is a write of its own, ending on its own.
        cache.end_writeback(done);
        ref.end_writeback(done.token);
        break;
      }
      case 6: {
        const std::int64_t amount = pick(1, 400);
        const FileId excluded = pick(0, 1) ? file : kNoFile;
        const GroupId group = target(pick(0, 2));
        REQUIRE(cache.evict(amount, excluded, group) == ref.evict(amount, excluded, group));
        break;
      }
      case 7: {  // application memory
        const auto group = static_cast<GroupId>(pick(0, static_cast<std::int64_t>(anonymous.size()) - 1));
        if (pick(0, 1)) {
          const std::int64_t bytes = pick(0, std::min<std::int64_t>(cache.free(), 200));
          cache.allocate_anonymous(bytes, group);
          ref.anonymous += bytes;
          anonymous[group] += bytes;
        } else {
          const std::int64_t bytes = pick(0, anonymous[group]);
          cache.release_anonymous(bytes, group);
          ref.anonymous -= bytes;
          anonymous[group] -= bytes;
        }
        break;
      }
      case 8: {  // a copy into the cache starts...
        const std::int64_t bytes = std::min<std::int64_t>(pick(1, 100), cache.free());
        cache.reserve(bytes);
        ref.reserved += bytes;
        copies.emplace_back(file, bytes);
        break;
      }
      case 9: {  // ... and ends
        if (copies.empty()) break;
        const auto [f, bytes] = copies.back();
        copies.pop_back();
        cache.commit_dirty(f, bytes, now);
        ref.reserved -= bytes;
        ref.add(f, bytes, BlockState::Dirty, now);
        break;
      }
      case 10: {  // more memory than is free cannot be taken
        const std::int64_t too_much = cache.free() + 1;
        REQUIRE_THROWS_AS(cache.add_clean(file, too_much, now), SimulationError);
        REQUIRE_THROWS_AS(cache.allocate_anonymous(too_much), SimulationError);
        break;
      }
      case 11:
        cache.walks().balance();
        ref.balance();
        break;
      case 12: {  // data read from a device by an application
        const std::int64_t bytes = std::min<std::int64_t>(pick(1, 120), cache.free());
        cache.add_read(file, bytes, now);
        ref.add(file, bytes, BlockState::Clean, now, settings.get("two_touch_activation"));
        break;
      }
      case 13: {  // a write of the file starts, or one ends (at most three at once per file)
        const bool start = ref.writers[file] == 0 || (ref.writers[file] < 3 && pick(0, 1));
        cache.set_being_written(file, start);
        ref.writers[file] += start ? 1 : -1;
        break;
      }
      case 14: {  // the file charged to a group, unless one has it already (the first keeps it)
        const auto group = static_cast<GroupId>(pick(1, 2));
        cache.charge_file(file, group);
        if (ref.group[file] == kRootGroup) ref.group[file] = group;
        REQUIRE(cache.groups().of(file) == ref.group[file]);
        break;
      }
      default:
        break;
    }
    compare(cache, ref, static_cast<std::uint64_t>(step));
  }
}

}  // namespace

TEST_CASE("PageCache agrees with the reference model over random operations (paper profile)", "[page_cache][random]") {
  for (std::uint64_t seed : {1u, 2u, 3u}) run_random(CacheSettings::paper(), seed, 20000);
}

TEST_CASE("the kernel policy with every switch at WRENCH-cache's value agrees with the reference as wrench_cache does",
          "[page_cache][random][policy]") {
  CacheSettings settings = CacheSettings::paper();
  settings.set("two_touch_activation", false);  // the kernel policy, every switch as the preset's
  for (std::uint64_t seed : {1u, 2u, 3u}) run_random(settings, seed, 20000);
}

TEST_CASE("PageCache agrees with the reference model over random operations (kernel settings)", "[page_cache][random]") {
  // The reference takes expired data in LRU order; the kernel profile's oldest-first order
  // (expire_oldest_first) has its own test in page_cache_test.cpp, and PageCache checks its
  // list by age after every step here too.
  CacheSettings settings = CacheSettings::kernel();
  settings.set("expire_oldest_first", false);
  for (std::uint64_t seed : {4u, 5u, 6u}) run_random(settings, seed, 20000);
}

TEST_CASE("PageCache agrees with the reference model over random operations (kernel settings, reclaiming active data too)",
          "[page_cache][random]") {
  // Eviction sparing the files being written also searches the active list.
  CacheSettings settings = CacheSettings::kernel();
  settings.set("expire_oldest_first", false);
  settings.set("reclaim_inactive_only", false);
  for (std::uint64_t seed : {7u, 8u, 9u}) run_random(settings, seed, 20000);
}

TEST_CASE("PageCache agrees with the reference model with memory groups: a group's eviction and flush take only its files",
          "[page_cache][random][groups]") {
  // Under the kernel settings eviction spares the files being written through each group's own
  // heap of reclaimable files; under the paper's it walks the lists.
  CacheSettings kernel = CacheSettings::kernel();
  kernel.set("expire_oldest_first", false);
  run_random(kernel, 10u, 20000, true);
  kernel.set("reclaim_inactive_only", false);
  run_random(kernel, 12u, 20000, true);
  run_random(CacheSettings::paper(), 13u, 20000, true);
}
