#pragma once
// FileRanges: each file's cached blocks by byte offset, so that a read or write of part of a
// file finds the blocks it touches. The blocks themselves stay in recency order on their
// lists; this is a second order over the same ids.
//
// A B+ tree per file, keyed by offset, of up to 32 entries per node (an offset and a BlockId
// each; in leaves the block's end too, so that a look-up learns a block's span from the leaf it
// reads anyway), its leaves linked both ways; each block's span also in a side array by
// BlockId, so that offset() costs one load. A node is fetched whole on a visit (prefetches of
// all its lines: one miss's wait, not one per line). A B+ tree, not a treap: a treap's 16 bytes
// per block come with some 28 levels under 10^6 blocks, each a cache miss on a random read;
// nor a std::map: a 48-byte allocation per block, as deep. A file's blocks hold disjoint
// ranges of non-zero size, so their offsets are distinct: the index asserts it. Nodes emptied
// by erases are freed; nodes left part-full are not merged (the depth only grows with the
// entries a file has held at once). tests/cache/file_ranges_test.cpp checks it against std::map.

#include "cache/block.hpp"

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace pagecache::cache {

class FileRanges {
 public:
  /// Reclaim and aging take files held by range in whole pages of `page_size` bytes (> 0; a
  /// reference model whose bytes stand for pages uses 1).
  explicit FileRanges(std::int64_t page_size = kPageSize) : page_size_(page_size) {}
  std::int64_t page_size() const noexcept { return page_size_; }

  /// From now on `file`'s blocks are indexed here (its first access by parts). Whether it is.
  void track(FileId file) {
    if (file >= tracked_.size()) tracked_.resize(static_cast<std::size_t>(file) + 1, 0);
    tracked_[file] = 1;
  }
  bool tracked(FileId file) const noexcept { return file < tracked_.size() && tracked_[file] != 0; }
  /// Cached bytes of [offset, offset + bytes) of a tracked file: its blocks' overlap with it.
  std::int64_t cached_in(FileId file, std::int64_t offset, std::int64_t bytes) const noexcept;

  /// Indexes `block` of `file`, [offset, offset + size). The block is not indexed already, and
  /// no block of the file has that offset.
  void insert(FileId file, BlockId block, std::int64_t offset, std::int64_t size);
  /// Takes `block` (indexed under `file`) out of the index.
  void erase(FileId file, BlockId block);
  /// Where `block` starts in its file, and where it ends (kept here beside the offset, so that
  /// a look-up learns whether a block holds an offset without reading the block: a cache miss
  /// under random access).
  std::int64_t offset(BlockId block) const noexcept { return spans_[block].offset; }
  std::int64_t end(BlockId block) const noexcept { return spans_[block].end; }
  /// `block` of `file` has a new size (its offset did not change).
  void resize(FileId file, BlockId block, std::int64_t size) noexcept;

  /// The block of `file` with the greatest offset <= `offset` (the one that holds `offset`, if
  /// any does), or kNoBlock.
  BlockId floor(FileId file, std::int64_t offset) const noexcept { return around(file, offset).floor.id; }
  /// A block and where it starts and ends (id kNoBlock: none).
  struct Located {
    BlockId id = kNoBlock;
    std::int64_t offset = 0;
    std::int64_t end = 0;
  };
  /// floor(file, offset) and the block after it (the least offset > `offset`), in one descent,
  /// with their spans: read from the leaf, where the side array would cost a cache miss each
  /// under random access.
  struct Around {
    Located floor;
    Located above;
  };
  Around around(FileId file, std::int64_t offset) const noexcept;
  /// The block of `file` that holds `offset` or, if none does, the first after it.
  Located at_or_after(FileId file, std::int64_t offset) const noexcept {
    const Around at = around(file, offset);
    return at.floor.id != kNoBlock && at.floor.end > offset ? at.floor : at.above;
  }
  /// The block of `file` with the least offset >= `offset`, or kNoBlock.
  BlockId ceiling(FileId file, std::int64_t offset) const noexcept;
  /// The block of `file` with the least offset, or kNoBlock.
  BlockId first(FileId file) const noexcept;
  /// The block of `file` with the greatest offset, or kNoBlock.
  BlockId last(FileId file) const noexcept;
  /// Where the file's last block ends (0: none).
  std::int64_t file_end(FileId file) const noexcept { return last(file) == kNoBlock ? 0 : spans_[last(file)].end; }
  /// The block after `block` by offset in its file, or kNoBlock.
  BlockId next(FileId file, BlockId block) const noexcept { return around(file, spans_[block].offset).above.id; }
  bool empty(FileId file) const noexcept { return tree(file).root == kNoNode; }
  /// Start loading what erasing `block` of `file` will read: its leaf (a descent through inner
  /// nodes, which stay cached), and, for a block whose turn comes later, its span.
  void prefetch_leaf(FileId file, BlockId block) const noexcept;
  void prefetch_span(BlockId block) const noexcept { __builtin_prefetch(&spans_[block]); }

  /// Calls `visit(block)` for every block of `file`, by offset (invariant checks, tests).
  template <class Visit>
  void for_each(FileId file, Visit&& visit) const {
    for (NodeId n = edge_leaf(file, false); n != kNoNode; n = nodes_[n].next) {
      for (int i = 0; i < nodes_[n].count; ++i) visit(static_cast<BlockId>(nodes_[n].ids[i]));
    }
  }
  /// Throws InvariantError unless the file's tree is ordered, balanced and linked, its
  /// entries' offsets are the side array's, their spans disjoint, and it holds at most `most`
  /// entries (more is a cycle), none if the file is not tracked; returns how many it holds.
  std::size_t check(FileId file, std::size_t most) const;

 private:
  using NodeId = std::uint32_t;
  static constexpr NodeId kNoNode = std::numeric_limits<NodeId>::max();
  static constexpr int kFan = 32;
  // Aligned, and its count and kind first, so that a visit starts with the line it scans first.
  struct alignas(64) Node {
    std::uint16_t count = 0;
    bool leaf = true;
    std::uint32_t generation = 0;  // bumped when the node is freed: a finger to it is stale
    NodeId prev = kNoNode;  // leaves: the file's leaves in order
    NodeId next = kNoNode;
    // Leaf: its blocks' offsets, ascending, and their ids. Inner: keys[i] (i >= 1) is the least
    // offset child i may hold, every offset of child i - 1 below it; keys[0] is unused.
    std::int64_t keys[kFan];
    std::uint32_t ids[kFan];
    std::int64_t ends[kFan];  // leaf: where each block ends (unused in inner nodes)
  };
  // The leaf the last descent ended in, and the offsets it covers ([low, high): its separators
  // on the way down). A chunk read looks up the same offset three or four times (its plan,
  // its read, the new block's insert); between them only erases elsewhere may happen, which
  // move no separator. A split anywhere, or the leaf freed, makes the finger stale.
  struct Finger {
    FileId file = 0;
    NodeId leaf = kNoNode;
    std::uint32_t generation = 0;
    std::uint64_t splits = 0;
    std::int64_t low = 0;
    std::int64_t high = 0;
  };
  struct Tree {
    NodeId root = kNoNode;
    int height = 0;  // 1: the root is a leaf
  };
  // A node split off by an insert, for its parent to take: its least key and its id.
  struct Split {
    std::int64_t key = 0;
    NodeId node = kNoNode;
  };

  const Tree& tree(FileId file) const noexcept {
    static const Tree none;
    return file < trees_.size() ? trees_[file] : none;
  }
  /// The child of inner node `n` whose range holds `key`.
  int child_for(const Node& n, std::int64_t key) const noexcept;
  /// The leftmost (or rightmost) leaf of the file's tree, or kNoNode.
  NodeId edge_leaf(FileId file, bool rightmost) const noexcept;
  NodeId new_node(bool leaf);
  /// Inserts under node `n`, `level` levels above the leaves; returns the node split off, if any.
  Split insert_below(NodeId n, int level, std::int64_t key, std::int64_t end, BlockId block);
  /// Moves the upper half of full node `n` into a new node, returned with its least key.
  Split split_node(NodeId n);
  /// Erases `key` under node `n`; returns whether `n` is now empty (and was freed, unless root).
  bool erase_below(NodeId n, int level, std::int64_t key, BlockId block, bool is_root);
  std::size_t check_node(NodeId n, int level, std::int64_t low, std::int64_t high, std::size_t most, std::size_t& seen,
                         std::vector<NodeId>& leaves) const;

  /// The leaf of the file's tree whose range holds `offset` (kNoNode: no tree), by the finger
  /// if it holds, else by a descent that sets it.
  NodeId leaf_for(FileId file, std::int64_t offset) const noexcept;
  /// Starts loading node `n` into the cache, all of it.
  void fetch(NodeId n) const noexcept;
  void free_node(NodeId n);

  std::vector<Node> nodes_;
  mutable Finger finger_;
  std::uint64_t splits_ = 0;
  std::vector<NodeId> free_nodes_;
  struct Span {
    std::int64_t offset;
    std::int64_t end;
  };
  std::vector<Span> spans_;  // by BlockId
  std::vector<Tree> trees_;            // by FileId
  // By FileId, whether it is held by range: beside the trees, as a reader of whole files asks.
  std::vector<std::uint8_t> tracked_;
  std::int64_t page_size_;
};

}  // namespace pagecache::cache
