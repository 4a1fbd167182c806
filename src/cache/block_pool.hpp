#pragma once
// BlockPool: where PageCache's blocks live, named by 32-bit ids: one array, so that following a
// link costs a shift and an add. Blocks are recycled through a free list, so that a simulation
// allocates no block once the pool has grown to its peak. The array grows by doubling with
// realloc, which glibc does for large arrays by remapping their pages, without copying them.
//
// Growing moves the blocks: a reference to a block is valid until the next take(); ids stay.
//
// A pool that ends leaves its array (up to 16 MiB) to the next pool of its thread, so that a
// sweep of runs does not fault in a fresh array's pages for every run. One array, not chunks,
// so that following a link is one load.

#include "cache/block.hpp"

#include <cstddef>
#include <cstdint>
#include <new>
#include <vector>

namespace pagecache::cache {

class BlockPool {
 public:
  BlockPool() = default;
  BlockPool(const BlockPool&) = delete;
  BlockPool& operator=(const BlockPool&) = delete;
  ~BlockPool();

  Block& operator[](BlockId id) noexcept { return blocks_[id]; }
  const Block& operator[](BlockId id) const noexcept { return blocks_[id]; }

  /// A block as Block(): the most recently given back (likely still in cache), or a new one.
  /// May move every block (see above).
  BlockId take() {
    if (free_.empty()) return take_fresh();
    const BlockId id = free_.back();
    free_.pop_back();
    blocks_[id] = Block();
    ++in_use_;
    return id;
  }
  void give_back(BlockId id) noexcept {
    free_.push_back(id);  // capacity reserved when the array grows: never reallocates here
    --in_use_;
  }
  std::size_t in_use() const noexcept { return in_use_; }

 private:
  // Out of line: only while the pool grows to its peak.
  [[gnu::noinline]] BlockId take_fresh() {
    if (fresh_ == capacity_) grow();
    const auto id = static_cast<BlockId>(fresh_++);
    ::new (static_cast<void*>(blocks_ + id)) Block();
    ++in_use_;
    return id;
  }
  void grow();

  void* raw_ = nullptr;       // as allocated: realloc keeps malloc's alignment, not a block's
  Block* blocks_ = nullptr;   // the array: the first 64-byte boundary in it
  std::size_t capacity_ = 0;  // blocks the array can hold
  std::size_t fresh_ = 0;     // blocks made so far: ids 0 .. fresh_ - 1
  std::vector<BlockId> free_;
  std::size_t in_use_ = 0;
};

}  // namespace pagecache::cache
