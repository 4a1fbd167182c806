#pragma once
// LruList: one of the page cache's two LRU lists (inactive or active), with O(1) byte
// counters, and sub-lists of its clean, dirty and writeback blocks kept in the list's own
// relative order. Front = least recently used.

#include "cache/block.hpp"

#include <array>
#include <cstddef>
#include <cstdint>

namespace pagecache::cache {

class LruList {
 public:
  explicit LruList(ListKind kind) noexcept : kind_(kind) {}
  LruList(const LruList&) = delete;
  LruList& operator=(const LruList&) = delete;
  ~LruList();

  ListKind kind() const noexcept { return kind_; }
  std::int64_t bytes() const noexcept { return bytes_; }
  std::int64_t bytes(BlockState state) const noexcept { return state_bytes_[index(state)]; }
  std::size_t size() const noexcept { return blocks_.size(); }
  std::size_t blocks_in(BlockState state) const noexcept { return by_state_[index(state)].size(); }
  bool empty() const noexcept { return blocks_.empty(); }

  /// Appends at the most-recently-used end, with an order key above every other's here.
  void push_back(Block& block);
  /// Inserts `block` right after `position` (a block of this list), with its order key: used
  /// when splitting.
  void insert_after(Block& position, Block& block);
  void erase(Block& block);
  /// Changes a block's state, keeping the state sub-lists in LRU order.
  void set_state(Block& block, BlockState state);
  /// Adjusts the byte counters after a block of this list changed size.
  void resize(Block& block, std::int64_t new_size);

  Block* front() noexcept { return blocks_.empty() ? nullptr : &blocks_.front(); }
  Block* back() noexcept { return blocks_.empty() ? nullptr : &blocks_.back(); }
  Block* next(Block& block) noexcept;
  /// Least recently used block in `state`, and the next one in that state.
  Block* front(BlockState state) noexcept;
  Block* next(Block& block, BlockState state) noexcept;

  const LruOrder& blocks() const noexcept { return blocks_; }

  /// Throws InvariantError if counters or sub-lists disagree with the blocks.
  void check() const;

 private:
  static std::size_t index(BlockState state) noexcept { return static_cast<std::size_t>(state); }
  void link_state(Block& block);

  ListKind kind_;
  LruOrder blocks_;
  std::array<StateOrder, 3> by_state_;
  std::int64_t bytes_ = 0;
  std::array<std::int64_t, 3> state_bytes_{};
  std::uint64_t last_order_ = 0;  // the order key of the last block appended
};

}  // namespace pagecache::cache
