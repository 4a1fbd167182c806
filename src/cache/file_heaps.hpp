#pragma once
// FileHeaps: files keyed by a number in one or more heaps, smallest key on top of each, a file
// in at most one of them and at most once: IndexedHeaps sharing one table of the files'
// indices, so that a file's key can be lowered, or a top's raised, in O(log files).
//
// PageCache keeps them per LRU list to find the next victim of an eviction that spares the
// files being written: its keys are lower bounds on the order keys of the files' first clean
// blocks (see PageCache::reclaimable_), in one heap for the whole host and in one heap a
// memory group for a group's own reclaim. Two files never share a key there, so a top is
// always the same file whatever the heap's shape.

#include "cache/block.hpp"
#include "engine/check.hpp"
#include "engine/indexed_heap.hpp"

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace pagecache::cache {

class FileHeaps {
 public:
  struct Entry {
    std::uint64_t key = 0;
    FileId file = 0;
  };

  explicit FileHeaps(std::size_t heaps = 1) { resize(heaps); }
  FileHeaps(const FileHeaps&) = delete;  // the heaps record indices in this one's table
  FileHeaps& operator=(const FileHeaps&) = delete;

  /// At least `heaps` heaps (never fewer than there are).
  void resize(std::size_t heaps) {
    while (heaps_.size() < heaps) heaps_.emplace_back(RecordIndex{&position_});
  }
  std::size_t heaps() const noexcept { return heaps_.size(); }
  bool empty(std::size_t heap) const noexcept { return heaps_[heap].empty(); }
  const Entry& top(std::size_t heap) const noexcept { return heaps_[heap].top(); }
  bool contains(FileId file) const noexcept { return file < position_.size() && position_[file] != kAbsent; }
  /// The key of `file`, which is in `heap`.
  std::uint64_t key(std::size_t heap, FileId file) const noexcept { return heaps_[heap].at(position_[file]).key; }

  /// Adds `file` to `heap` with `key`, or lowers its key there to `key` if that is lower. A
  /// file already in the heaps must be in `heap`.
  void lower(std::size_t heap, FileId file, std::uint64_t key) {
    if (file >= position_.size()) position_.resize(static_cast<std::size_t>(file) + 1, kAbsent);
    if (!contains(file)) heaps_[heap].push({key, file});
    else if (key < this->key(heap, file)) heaps_[heap].replace(position_[file], {key, file});
  }
  /// Raises the top's key to `key`.
  void raise_top(std::size_t heap, std::uint64_t key) {
    PC_ASSERT(!heaps_[heap].empty() && key > heaps_[heap].top().key);
    heaps_[heap].replace(0, {key, heaps_[heap].top().file});
  }
  void pop(std::size_t heap) {
    PC_ASSERT(!heaps_[heap].empty());
    position_[heaps_[heap].top().file] = kAbsent;
    heaps_[heap].pop();
  }

  /// Calls `visit(entry)` for each entry of `heap`, in no particular order.
  template <class Visit>
  void for_each(std::size_t heap, Visit&& visit) const {
    for (const Entry& e : heaps_[heap]) visit(e);
  }

  /// Throws InvariantError if a heap's order or the positions are broken.
  void check() const {
    std::size_t listed = 0;
    for (const Heap& heap : heaps_) {
      PC_ASSERT_MSG(heap.ordered(), "file heap out of order");
      std::size_t index = 0;
      for (const Entry& e : heap) {
        PC_ASSERT_MSG(contains(e.file) && position_[e.file] == index, "file heap position wrong");
        ++index;
      }
      listed += heap.size();
    }
    std::size_t present = 0;
    for (std::uint32_t p : position_) present += p != kAbsent;
    PC_ASSERT_MSG(present == listed, "file heaps hold a position for a file in none of them");
  }

 private:
  static constexpr std::uint32_t kAbsent = std::numeric_limits<std::uint32_t>::max();

  struct SmallerKey {
    bool operator()(const Entry& a, const Entry& b) const noexcept { return a.key < b.key; }
  };
  struct RecordIndex {
    std::vector<std::uint32_t>* position;
    void operator()(const Entry& e, std::uint32_t index) const noexcept { (*position)[e.file] = index; }
  };
  using Heap = detail::IndexedHeap<Entry, SmallerKey, RecordIndex>;

  std::vector<std::uint32_t> position_;  // by file: its index in its heap, or kAbsent
  std::vector<Heap> heaps_;
};

}  // namespace pagecache::cache
