#pragma once
// IndexedHeap: a 4-ary min-heap in one array whose elements know where they are, so that any
// of them can be removed or re-keyed in O(log n) without handles allocated per element.
//
// Entries are small values (a key, a tie-breaker, a pointer to their owner) stored in the
// array itself, so comparisons stay within it; whenever an entry moves, `Place` tells its
// owner its new index. Boost.Heap's mutable heaps (the style guide's default) keep their
// values in a std::list and allocate a node per push, which this heap avoids.
//
//   Before(a, b): true if a comes out first.   Place(entry, index): entry now lives at index.

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace pagecache::detail {

template <class Entry, class Before, class Place>
class IndexedHeap {
 public:
  using Index = std::uint32_t;

  IndexedHeap() = default;
  /// For a `Place` that needs state of its own (where it records the indices).
  explicit IndexedHeap(Place place) : place_(place) {}

  bool empty() const noexcept { return entries_.empty(); }
  std::size_t size() const noexcept { return entries_.size(); }
  const Entry& top() const noexcept { return entries_.front(); }
  const Entry& at(Index index) const noexcept { return entries_[index]; }
  auto begin() const noexcept { return entries_.begin(); }
  auto end() const noexcept { return entries_.end(); }

  void push(const Entry& entry) {
    entries_.push_back(entry);
    sift_up(static_cast<Index>(entries_.size() - 1));
  }
  void pop() noexcept { erase(0); }
  void erase(Index index) noexcept {
    const Index last = static_cast<Index>(entries_.size() - 1);
    if (index != last) {
      entries_[index] = std::move(entries_[last]);
      entries_.pop_back();
      restore(index);
    } else {
      entries_.pop_back();
    }
  }
  /// Replaces the entry at `index` (its key changed) and restores the order.
  void replace(Index index, const Entry& entry) noexcept {
    entries_[index] = entry;
    restore(index);
  }
  void clear() noexcept { entries_.clear(); }

  // Unordered use: while nobody asks for its top, a holder may keep the entries as a plain
  // array, where adding or removing one moves at most one other, and order them when needed.
  // top() and the ordered operations are only valid once make_ordered() has run.
  void push_unordered(const Entry& entry) {
    entries_.push_back(entry);
    place_(entries_.back(), static_cast<Index>(entries_.size() - 1));
  }
  void erase_unordered(Index index) noexcept {
    const Index last = static_cast<Index>(entries_.size() - 1);
    if (index != last) {
      entries_[index] = std::move(entries_[last]);
      place_(entries_[index], index);
    }
    entries_.pop_back();
  }
  /// Orders the entries into a heap, in O(n).
  void make_ordered() noexcept {
    const Index size = static_cast<Index>(entries_.size());
    if (size < 2) return;
    for (Index i = (size - 2) / kArity + 1; i-- > 0;) sift_down(i);
  }
  /// True if no entry would come out before its parent: for invariant checks.
  bool ordered() const noexcept {
    for (Index i = 1; i < entries_.size(); ++i) {
      if (before_(entries_[i], entries_[(i - 1) / kArity])) return false;
    }
    return true;
  }

 private:
  static constexpr Index kArity = 4;

  void restore(Index index) noexcept {
    if (index > 0 && before_(entries_[index], entries_[(index - 1) / kArity])) sift_up(index);
    else sift_down(index);
  }
  void sift_up(Index index) noexcept {
    Entry moving = std::move(entries_[index]);
    while (index > 0) {
      const Index parent = (index - 1) / kArity;
      if (!before_(moving, entries_[parent])) break;
      entries_[index] = std::move(entries_[parent]);
      place_(entries_[index], index);
      index = parent;
    }
    entries_[index] = std::move(moving);
    place_(entries_[index], index);
  }
  void sift_down(Index index) noexcept {
    const Index size = static_cast<Index>(entries_.size());
    Entry moving = std::move(entries_[index]);
    for (;;) {
      const Index first = index * kArity + 1;
      if (first >= size) break;
      Index best = first;
      const Index stop = first + kArity < size ? first + kArity : size;
      for (Index child = first + 1; child < stop; ++child) {
        if (before_(entries_[child], entries_[best])) best = child;
      }
      if (!before_(entries_[best], moving)) break;
      entries_[index] = std::move(entries_[best]);
      place_(entries_[index], index);
      index = best;
    }
    entries_[index] = std::move(moving);
    place_(entries_[index], index);
  }

  std::vector<Entry> entries_;
  [[no_unique_address]] Before before_;
  [[no_unique_address]] Place place_;
};

}  // namespace pagecache::detail
