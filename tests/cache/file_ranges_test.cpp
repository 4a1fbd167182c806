// FileRanges, the per-file index of blocks by offset (a B+ tree per file): hand cases, then random inserts, erases,
// splits (a block cut in two: the tail indexed at head offset + head size) and look-ups over
// several files and seeds, checked against a std::map per file; ids recycled as the pool does.
#include "cache/file_ranges.hpp"

#include <pagecache/error.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <iterator>
#include <map>
#include <random>
#include <vector>

using namespace pagecache::cache;

namespace {

// A block of the reference: its id and size, by offset.
struct Range {
  BlockId id;
  std::int64_t size;
};
using Reference = std::map<std::int64_t, Range>;

BlockId floor_of(const Reference& ref, std::int64_t offset) {
  auto it = ref.upper_bound(offset);
  return it == ref.begin() ? kNoBlock : std::prev(it)->second.id;
}

// The bytes of [offset, offset + bytes) the reference's blocks hold, by visiting them all.
std::int64_t cached_in_of(const Reference& ref, std::int64_t offset, std::int64_t bytes) {
  std::int64_t cached = 0;
  for (const auto& [start, range] : ref) cached += std::max<std::int64_t>(0, std::min(offset + bytes, start + range.size) - std::max(offset, start));
  return cached;
}

BlockId ceiling_of(const Reference& ref, std::int64_t offset) {
  auto it = ref.lower_bound(offset);
  return it == ref.end() ? kNoBlock : it->second.id;
}

void check_order(const FileRanges& index, FileId file, const Reference& ref) {
  std::vector<BlockId> want;
  for (const auto& [offset, range] : ref) want.push_back(range.id);
  std::vector<BlockId> walked;
  index.for_each(file, [&](BlockId id) { walked.push_back(id); });
  REQUIRE(walked == want);
  std::vector<BlockId> stepped;
  for (BlockId id = index.first(file); id != kNoBlock; id = index.next(file, id)) stepped.push_back(id);
  REQUIRE(stepped == want);
  REQUIRE(index.check(file, ref.size()) == ref.size());
  REQUIRE(index.empty(file) == ref.empty());
}

}  // namespace

TEST_CASE("A file's blocks are found by offset, whatever order they came in") {
  FileRanges index;
  REQUIRE(index.first(0) == kNoBlock);
  REQUIRE(index.floor(3, 100) == kNoBlock);
  index.track(0);
  index.track(1);
  REQUIRE(!index.tracked(2));
  index.insert(0, 7, 4096, 4096);
  index.insert(0, 2, 0, 4096);
  index.insert(0, 9, 8192, 4096);
  index.insert(1, 3, 0, 10);  // another file's block at the same offset
  REQUIRE(index.floor(0, 4095) == 2);
  REQUIRE(index.floor(0, 4096) == 7);
  REQUIRE(index.floor(0, 1 << 20) == 9);
  REQUIRE(index.ceiling(0, 1) == 7);
  REQUIRE(index.ceiling(0, 8193) == kNoBlock);
  REQUIRE(index.first(0) == 2);
  REQUIRE(index.next(0, 2) == 7);
  REQUIRE(index.next(0, 9) == kNoBlock);
  REQUIRE(index.offset(9) == 8192);
  REQUIRE(index.floor(1, 5) == 3);
  REQUIRE(index.cached_in(0, 100, 8000) == 8000);
  REQUIRE(index.cached_in(0, 10000, 10000) == 12288 - 10000);
  REQUIRE(index.cached_in(1, 5, 100) == 5);
  index.erase(0, 7);
  REQUIRE(index.cached_in(0, 100, 8000) == 4096 - 100);  // block 9 starts after the range
  REQUIRE(index.next(0, 2) == 9);
  REQUIRE(index.floor(0, 5000) == 2);
  index.erase(0, 2);
  index.erase(0, 9);
  REQUIRE(index.empty(0));
  REQUIRE(!index.empty(1));
}

TEST_CASE("A file not held by range has no offsets indexed (the check)") {
  FileRanges index;
  index.insert(4, 1, 0, 4096);
  REQUIRE_THROWS_AS(index.check(4, 1), pagecache::InvariantError);
  index.track(4);
  REQUIRE(index.check(4, 1) == 1);
}

TEST_CASE("Two blocks of one file at one offset are refused") {
  FileRanges index;
  index.track(0);
  for (BlockId id = 0; id < 64; ++id) index.insert(0, id, 4096 * std::int64_t{id}, 4096);
  // Either on the way down or by the check, depending on where the new node lands.
  bool refused = false;
  try {
    index.insert(0, 100, 4096 * 17, 4096);
    index.check(0, 65);
  } catch (const pagecache::InvariantError&) {
    refused = true;
  }
  REQUIRE(refused);
}

TEST_CASE("A file read in order stays shallow: 10^5 blocks appended by offset") {
  FileRanges index;
  index.track(0);
  constexpr BlockId n = 100000;
  for (BlockId id = 0; id < n; ++id) index.insert(0, id, std::int64_t{id} * 4096, 4096);
  REQUIRE(index.check(0, n) == n);
  REQUIRE(index.floor(0, 4096 * 5000 + 17) == 5000);
  for (BlockId id = 0; id < n; id += 2) index.erase(0, id);
  REQUIRE(index.first(0) == 1);
  REQUIRE(index.check(0, n) == n / 2);
}

TEST_CASE("Random inserts, erases, splits and look-ups agree with std::map") {
  const auto seed = GENERATE(1u, 2u, 3u, 38u, 2026u);
  std::mt19937_64 rng(seed);
  constexpr FileId kFiles = 5;
  constexpr std::int64_t kFileSize = 1 << 24;
  FileRanges index;
  for (FileId file = 0; file < kFiles; ++file) index.track(file);
  std::vector<Reference> refs(kFiles);
  std::vector<BlockId> free_ids;
  BlockId fresh = 0;
  auto take_id = [&] {
    if (free_ids.empty()) return fresh++;
    const BlockId id = free_ids.back();
    free_ids.pop_back();
    return id;
  };
  auto pick = [&](Reference& ref) {
    return std::next(ref.begin(), static_cast<long>(rng() % ref.size()));
  };
  for (int step = 0; step < 120000; ++step) {
    const auto file = static_cast<FileId>(rng() % kFiles);
    Reference& ref = refs[file];
    const std::int64_t at = static_cast<std::int64_t>(rng() % kFileSize);
    switch (rng() % 8) {
      case 0:
      case 1: {  // new data in a hole, up to the next block
        const auto next = ref.lower_bound(at);
        if (floor_of(ref, at) != kNoBlock) {
          const auto& [start, range] = *std::prev(next);
          if (start + range.size > at) break;  // inside a block: no hole here
        }
        if (next != ref.end() && next->first == at) break;
        const std::int64_t room = (next == ref.end() ? kFileSize : next->first) - at;
        const std::int64_t size = 1 + static_cast<std::int64_t>(rng() % static_cast<std::uint64_t>(room));
        const BlockId id = take_id();
        index.insert(file, id, at, size);
        ref[at] = {id, size};
        break;
      }
      case 2: {  // a block evicted or dropped
        if (ref.empty()) break;
        const auto it = pick(ref);
        index.erase(file, it->second.id);
        free_ids.push_back(it->second.id);
        ref.erase(it);
        break;
      }
      case 3: {  // a block split: the tail follows its head
        if (ref.empty()) break;
        const auto it = pick(ref);
        if (it->second.size < 2) break;
        const std::int64_t head = 1 + static_cast<std::int64_t>(rng() % static_cast<std::uint64_t>(it->second.size - 1));
        const BlockId tail = take_id();
        index.insert(file, tail, it->first + head, it->second.size - head);
        index.resize(file, it->second.id, head);
        ref[it->first + head] = {tail, it->second.size - head};
        it->second.size = head;
        break;
      }
      default: {  // look-ups
        REQUIRE(index.floor(file, at) == floor_of(ref, at));
        REQUIRE(index.ceiling(file, at) == ceiling_of(ref, at));
        const auto above = ref.upper_bound(at);
        const FileRanges::Around found = index.around(file, at);
        REQUIRE(found.above.id == (above == ref.end() ? kNoBlock : above->second.id));
        if (above != ref.end()) {
          REQUIRE(found.above.offset == above->first);
          REQUIRE(found.above.end == above->first + above->second.size);
        }
        REQUIRE(found.floor.id == floor_of(ref, at));
        if (above != ref.begin()) {
          const auto floor = std::prev(above);
          REQUIRE(found.floor.offset == floor->first);
          REQUIRE(found.floor.end == floor->first + floor->second.size);
        }
        // The block holding `at`, else the first after it.
        const bool held = above != ref.begin() && std::prev(above)->first + std::prev(above)->second.size > at;
        REQUIRE(index.at_or_after(file, at).id == (held ? std::prev(above)->second.id : found.above.id));
        if (step % 16 == 4) {  // a range's cached bytes (a walk of the whole reference: not every time)
          const std::int64_t bytes = static_cast<std::int64_t>(rng() % (kFileSize / 64));
          REQUIRE(index.cached_in(file, at, bytes) == cached_in_of(ref, at, bytes));
        }
        if (!ref.empty()) {
          const auto it = pick(ref);
          REQUIRE(index.offset(it->second.id) == it->first);
          REQUIRE(index.end(it->second.id) == it->first + it->second.size);
          const auto after = std::next(it);
          REQUIRE(index.next(file, it->second.id) == (after == ref.end() ? kNoBlock : after->second.id));
        }
        break;
      }
    }
    if (step % 4000 == 0) check_order(index, file, ref);
  }
  for (FileId file = 0; file < kFiles; ++file) check_order(index, file, refs[file]);
}
