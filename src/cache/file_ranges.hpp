#pragma once
// FileRanges: each file's cached blocks by byte offset, so that a read or write of part of a
// file finds the blocks it touches (issue 38). The blocks themselves stay in recency order on
// their lists; this is a second order over the same ids.
//
// An intrusive treap per file: a node per BlockId in one side array (a block is a full cache
// line, so its offset and two links live here, 16 bytes, indexed as the pool is), keyed by
// offset, heap-ordered by a hash of the id (no stored priority; ids are unique among live
// blocks). Chosen over a std::map per file (a 48-byte allocation per block, pointer chasing
// across the heap) and a sorted vector per file (O(n) inserts under random access). A file's
// blocks hold disjoint ranges of non-zero size, so their offsets are distinct: the index
// asserts it. Queries cost O(log blocks of the file), expected; sequential files stay a few
// blocks. tests/cache/file_ranges_test.cpp checks it against std::map.

#include "cache/block.hpp"

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace pagecache::cache {

class FileRanges {
 public:
  /// Indexes `block` of `file` at `offset`. The block is not indexed already, and no block of
  /// the file has that offset.
  void insert(FileId file, BlockId block, std::int64_t offset);
  /// Takes `block` (indexed under `file`) out of the index.
  void erase(FileId file, BlockId block);
  /// Where `block` starts in its file (as last inserted).
  std::int64_t offset(BlockId block) const noexcept { return nodes_[block].offset; }

  /// The block of `file` with the greatest offset <= `offset` (the one that holds `offset`, if
  /// any does), or kNoBlock.
  BlockId floor(FileId file, std::int64_t offset) const noexcept;
  /// floor(file, offset) and the block after it (the least offset > `offset`), in one descent.
  struct Around {
    BlockId floor = kNoBlock;
    BlockId above = kNoBlock;
  };
  Around around(FileId file, std::int64_t offset) const noexcept;
  /// The block of `file` with the least offset >= `offset`, or kNoBlock.
  BlockId ceiling(FileId file, std::int64_t offset) const noexcept;
  /// The block of `file` with the least offset, or kNoBlock.
  BlockId first(FileId file) const noexcept { return ceiling(file, kLowest); }
  /// The block of `file` with the greatest offset, or kNoBlock.
  BlockId last(FileId file) const noexcept { return floor(file, std::numeric_limits<std::int64_t>::max()); }
  /// The block after `block` by offset in its file, or kNoBlock.
  BlockId next(FileId file, BlockId block) const noexcept;
  bool empty(FileId file) const noexcept { return root(file) == kNoBlock; }

  /// Calls `visit(block)` for every block of `file`, by offset (invariant checks, tests).
  template <class Visit>
  void for_each(FileId file, Visit&& visit) const {
    walk(root(file), visit);
  }
  /// Throws InvariantError unless the file's tree is ordered by offset and by priority and
  /// holds at most `most` nodes (more is a cycle); returns how many it holds.
  std::size_t check(FileId file, std::size_t most) const;

 private:
  struct Node {
    std::int64_t offset = 0;
    BlockId left = kNoBlock;
    BlockId right = kNoBlock;
  };
  static constexpr std::int64_t kLowest = std::numeric_limits<std::int64_t>::min();

  /// The heap order: a well-mixed hash of the id, ties (never for distinct ids) by id.
  static std::uint32_t priority(BlockId id) noexcept {
    std::uint32_t h = id * 0x9E3779B1u;  // murmur3's finaliser after a multiplicative spread
    h ^= h >> 16;
    h *= 0x85EBCA6Bu;
    h ^= h >> 13;
    h *= 0xC2B2AE35u;
    return h ^ (h >> 16);
  }
  static bool above(BlockId a, BlockId b) noexcept {
    const std::uint32_t pa = priority(a);
    const std::uint32_t pb = priority(b);
    return pa != pb ? pa > pb : a > b;
  }
  BlockId root(FileId file) const noexcept { return file < roots_.size() ? roots_[file] : kNoBlock; }
  /// Splits the tree at `t` into offsets < `offset` (into `less`) and >= it (into `rest`).
  void split(BlockId t, std::int64_t offset, BlockId& less, BlockId& rest) noexcept;
  /// Joins two trees, every offset of `a` below every offset of `b`.
  BlockId merge(BlockId a, BlockId b) noexcept;
  template <class Visit>
  void walk(BlockId t, Visit& visit) const {
    while (t != kNoBlock) {  // right children iteratively: recursion only as deep as left links
      walk(nodes_[t].left, visit);
      visit(t);
      t = nodes_[t].right;
    }
  }
  std::size_t check_subtree(BlockId t, std::int64_t low, std::int64_t high, std::size_t most, std::size_t& seen) const;

  std::vector<Node> nodes_;    // by BlockId; grown to the highest id inserted
  std::vector<BlockId> roots_;  // by FileId
};

}  // namespace pagecache::cache
