#pragma once
// FileHeap: files keyed by a number, smallest key on top, each at most once: an IndexedHeap
// with the files' indices kept in a table by file, so that a file's key can be lowered, or
// the top's raised, in O(log files).
//
// PageCache keeps one per LRU list to find the next victim of an eviction that spares the
// files being written: its keys are lower bounds on the order keys of the files' first clean
// blocks (see PageCache::reclaimable_). Two files never share a key there, so the top is
// always the same file whatever the heap's shape.

#include "cache/block.hpp"
#include "engine/check.hpp"
#include "engine/indexed_heap.hpp"

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace pagecache::cache {

class FileHeap {
 public:
  struct Entry {
    std::uint64_t key = 0;
    FileId file = 0;
  };

  FileHeap() = default;
  FileHeap(const FileHeap&) = delete;  // the heap records indices in this one's table
  FileHeap& operator=(const FileHeap&) = delete;

  bool empty() const noexcept { return heap_.empty(); }
  const Entry& top() const noexcept { return heap_.top(); }
  bool contains(FileId file) const noexcept { return file < position_.size() && position_[file] != kAbsent; }
  std::uint64_t key(FileId file) const noexcept { return heap_.at(position_[file]).key; }

  /// Adds `file` with `key`, or lowers its key to `key` if that is lower.
  void lower(FileId file, std::uint64_t key) {
    if (file >= position_.size()) position_.resize(static_cast<std::size_t>(file) + 1, kAbsent);
    if (!contains(file)) heap_.push({key, file});
    else if (key < this->key(file)) heap_.replace(position_[file], {key, file});
  }
  /// Raises the top's key to `key`.
  void raise_top(std::uint64_t key) {
    PC_ASSERT(!heap_.empty() && key > heap_.top().key);
    heap_.replace(0, {key, heap_.top().file});
  }
  void pop() {
    PC_ASSERT(!heap_.empty());
    position_[heap_.top().file] = kAbsent;
    heap_.pop();
  }

  /// Throws InvariantError if the heap order or the positions are broken.
  void check() const {
    PC_ASSERT_MSG(heap_.ordered(), "file heap out of order");
    std::size_t present = 0;
    std::size_t index = 0;
    for (const Entry& e : heap_) {
      PC_ASSERT_MSG(contains(e.file) && position_[e.file] == index, "file heap position wrong");
      ++index;
    }
    for (std::uint32_t p : position_) present += p != kAbsent;
    PC_ASSERT_MSG(present == heap_.size(), "file heap holds a position for a file not in it");
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

  std::vector<std::uint32_t> position_;  // by file: its index in heap_, or kAbsent
  detail::IndexedHeap<Entry, SmallerKey, RecordIndex> heap_{RecordIndex{&position_}};
};

}  // namespace pagecache::cache
