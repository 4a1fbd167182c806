#pragma once
// LruList: one of the page cache's two LRU lists (inactive or active), with O(1) byte
// counters, and sub-lists of its clean, dirty and writeback blocks kept in the list's own
// relative order; clean blocks have one sub-list per NUMA node, so that a node's reclaim finds
// its own (docs/model.md §6.20). Front = least recently used. Blocks are named by id in the
// pool the list was made with.

#include "cache/block.hpp"
#include "cache/block_list.hpp"
#include "cache/block_pool.hpp"
#include "cache/numa_nodes.hpp"

#include <array>
#include <cstddef>
#include <cstdint>

namespace pagecache::cache {

using LruOrder = BlockList<&Block::lru, true>;
using StateOrder = BlockList<&Block::by_state, true>;

class LruList {
 public:
  LruList(ListKind kind, BlockPool& pool) noexcept : kind_(kind), pool_(&pool) {}
  LruList(const LruList&) = delete;
  LruList& operator=(const LruList&) = delete;

  ListKind kind() const noexcept { return kind_; }
  std::int64_t bytes() const noexcept { return bytes_; }
  std::int64_t bytes(BlockState state) const noexcept { return state_bytes_[index(state)]; }
  std::size_t size() const noexcept { return blocks_.size(); }
  std::size_t blocks_in(BlockState state) const noexcept;
  bool empty() const noexcept { return blocks_.empty(); }

  /// Appends at the most-recently-used end, with an order key above every other's here.
  void push_back(BlockId block);
  /// Inserts at the least-recently-used end, with an order key below every other's here.
  void push_front(BlockId block);
  /// Inserts `block` right after `position` (a block of this list), with its order key: used
  /// when splitting.
  void insert_after(BlockId position, BlockId block);
  void erase(BlockId block);
  /// Changes a block's state, keeping the state sub-lists in LRU order.
  void set_state(BlockId block, BlockState state);
  /// Adjusts the byte counters after a block of this list changed size.
  void resize(BlockId block, std::int64_t new_size);

  /// kNoBlock where there is none.
  BlockId front() const noexcept { return blocks_.front(); }
  BlockId back() const noexcept { return blocks_.back(); }
  BlockId next(BlockId block) const noexcept { return LruOrder::next(*pool_, block); }
  /// A block of the list (or of another list sharing its pool).
  const Block& block(BlockId block) const noexcept { return (*pool_)[block]; }
  /// Least recently used block in `state` (clean: of `node`), and the next one in the state
  /// (clean: and node) of `block`. A one-node host's blocks are all on node 0.
  BlockId front(BlockState state, NodeId node = 0) const noexcept { return by_state_[sub_list(state, node)].front(); }
  BlockId next_in_state(BlockId block) const noexcept { return StateOrder::next(*pool_, block); }

  /// The blocks in LRU order, for checks and tests.
  LruOrder::Range blocks() const { return blocks_.range(*pool_); }

  /// Throws InvariantError if counters or sub-lists disagree with the blocks.
  void check() const;

 private:
  static std::size_t index(BlockState state) noexcept { return static_cast<std::size_t>(state); }
  // Clean, dirty, writeback, then the clean blocks of the nodes after node 0.
  static constexpr std::size_t kSubLists = 3 + kMaxNodes - 1;
  static std::size_t sub_list(BlockState state, NodeId node) noexcept {
    return state == BlockState::Clean && node > 0 ? 2 + static_cast<std::size_t>(node) : index(state);
  }
  static std::size_t sub_list(const Block& block) noexcept { return sub_list(block.state, block.node); }
  void link_state(BlockId block);

  ListKind kind_;
  BlockPool* pool_;
  LruOrder blocks_;
  std::array<StateOrder, kSubLists> by_state_;
  std::int64_t bytes_ = 0;
  std::array<std::int64_t, 3> state_bytes_{};
  // The order keys of the last block appended and of the last put at the front: keys start in
  // the middle of their range, so that either end has room.
  std::uint64_t last_order_ = std::uint64_t{1} << 62;
  std::uint64_t first_order_ = std::uint64_t{1} << 62;
};

}  // namespace pagecache::cache
