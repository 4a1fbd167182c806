#pragma once
// BlockList: an intrusive doubly linked list of blocks through one of their BlockLinks, by id
// (see Block). The list holds its ends (and, if Counted, its length); the blocks hold the
// links, so every operation takes the pool they live in. Unlinking a block resets its links.
// In debug builds (as Boost.Intrusive's safe-link hooks do), linking checks that they were
// reset and unlinking that the block is a member: a block linked twice is an InvariantError.
// Release builds leave those checks to check_invariants, off the hot path.
//
// link_in_order: puts a block into a sub-list kept in the relative order of a list that holds
// it (an LRU list's state sub-lists, a file's clean blocks within its file list).

#include "cache/block.hpp"
#include "cache/block_pool.hpp"
#include "engine/check.hpp"

#include <cstddef>
#include <cstdint>
#include <iterator>
#include <type_traits>

#ifdef NDEBUG
#define PC_CHECK_LINKS(cond) static_cast<void>(0)
#else
#define PC_CHECK_LINKS(cond) PC_ASSERT(cond)
#endif

namespace pagecache::cache {

template <BlockLinks Block::*Links, bool Counted>
class BlockList {
 public:
  bool empty() const noexcept { return head_ == kNoBlock; }
  BlockId front() const noexcept { return head_; }
  BlockId back() const noexcept { return tail_; }
  /// Number of blocks (counted lists only).
  std::size_t size() const noexcept
    requires Counted
  {
    return count_.n;
  }
  static BlockId next(const BlockPool& pool, BlockId id) noexcept { return (pool[id].*Links).next; }
  static BlockId prev(const BlockPool& pool, BlockId id) noexcept { return (pool[id].*Links).prev; }

  void push_back(BlockPool& pool, BlockId id) { link(pool, id, tail_, kNoBlock); }
  void push_front(BlockPool& pool, BlockId id) { link(pool, id, kNoBlock, head_); }
  /// Links `id` right after `position`, a member.
  void insert_after(BlockPool& pool, BlockId position, BlockId id) {
    link(pool, id, position, (pool[position].*Links).next);
  }
  /// Links `id` right before `position`, a member.
  void insert_before(BlockPool& pool, BlockId position, BlockId id) {
    link(pool, id, (pool[position].*Links).prev, position);
  }
  void erase(BlockPool& pool, BlockId id) {
    BlockLinks& links = pool[id].*Links;
    PC_CHECK_LINKS(links.prev != kNoBlock || head_ == id);
    if (links.prev != kNoBlock) (pool[links.prev].*Links).next = links.next;
    else head_ = links.next;
    if (links.next != kNoBlock) (pool[links.next].*Links).prev = links.prev;
    else tail_ = links.prev;
    links = BlockLinks{};
    if constexpr (Counted) --count_.n;
  }

  /// Forward iteration over the blocks, for checks and tests.
  class Range {
   public:
    class iterator {
     public:
      using iterator_category = std::forward_iterator_tag;
      using value_type = Block;
      using difference_type = std::ptrdiff_t;
      using pointer = const Block*;
      using reference = const Block&;
      iterator() = default;
      iterator(const BlockPool* pool, BlockId id) : pool_(pool), id_(id) {}
      reference operator*() const { return (*pool_)[id_]; }
      pointer operator->() const { return &(*pool_)[id_]; }
      iterator& operator++() {
        id_ = ((*pool_)[id_].*Links).next;
        return *this;
      }
      iterator operator++(int) {
        iterator before = *this;
        ++*this;
        return before;
      }
      BlockId id() const noexcept { return id_; }
      friend bool operator==(const iterator& a, const iterator& b) noexcept { return a.id_ == b.id_; }

     private:
      const BlockPool* pool_ = nullptr;
      BlockId id_ = kNoBlock;
    };
    Range(const BlockPool& pool, const BlockList& list) : pool_(&pool), list_(&list) {}
    iterator begin() const { return {pool_, list_->head_}; }
    iterator end() const { return {pool_, kNoBlock}; }
    const Block& front() const { return (*pool_)[list_->head_]; }
    std::size_t size() const noexcept
      requires Counted
    {
      return list_->size();
    }

   private:
    const BlockPool* pool_;
    const BlockList* list_;
  };
  Range range(const BlockPool& pool) const { return Range(pool, *this); }

 private:
  void link(BlockPool& pool, BlockId id, BlockId prev, BlockId next) {
    BlockLinks& links = pool[id].*Links;
    PC_CHECK_LINKS(links.prev == kNoBlock && links.next == kNoBlock && head_ != id);
    links = {prev, next};
    if (prev != kNoBlock) (pool[prev].*Links).next = id;
    else head_ = id;
    if (next != kNoBlock) (pool[next].*Links).prev = id;
    else tail_ = id;
    if constexpr (Counted) ++count_.n;
  }

  struct Count {
    std::uint32_t n = 0;
  };
  struct NoCount {};
  BlockId head_ = kNoBlock;
  BlockId tail_ = kNoBlock;
  [[no_unique_address]] std::conditional_t<Counted, Count, NoCount> count_;
};

/// Links block `id`, a member of `list`, into `sub` (whose members satisfy `member` and are all
/// in `list`, in its order): right after the nearest member before it in `list`, or right
/// before the nearest one after it. Both ways are walked in turn, so the cost is the distance
/// to the nearer of the two (usually a neighbour), not to the list's end; a block with no
/// member before it, or at the end of `list`, is placed at once.
template <class List, class SubList, class IsMember>
void link_in_order(BlockPool& pool, const List& list, SubList& sub, BlockId id, IsMember member) {
  if (sub.empty() || list.back() == id) {
    sub.push_back(pool, id);
    return;
  }
  BlockId back = id;
  BlockId ahead = List::next(pool, id);
  for (;;) {
    if (back == list.front()) {
      sub.push_front(pool, id);  // no member before it: it goes first
      return;
    }
    back = List::prev(pool, back);
    if (member(pool[back])) {
      sub.insert_after(pool, back, id);
      return;
    }
    if (ahead == kNoBlock) {
      sub.push_back(pool, id);  // no member after it: it goes last
      return;
    }
    if (member(pool[ahead])) {
      sub.insert_before(pool, ahead, id);
      return;
    }
    ahead = List::next(pool, ahead);
  }
}

}  // namespace pagecache::cache
