#pragma once
// FileHeap: files keyed by a number, smallest key on top: a binary min-heap that knows where
// each file sits, so a file's key can be lowered, or the top's raised, in O(log files) without
// allocating once it has grown. A file is in it at most once.
//
// PageCache keeps one per LRU list to find the next victim of an eviction that spares the
// files being written: its keys are lower bounds on the order keys of the files' first clean
// blocks (see PageCache::reclaimable_).

#include "cache/block.hpp"
#include "engine/check.hpp"

#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace pagecache::cache {

class FileHeap {
 public:
  struct Entry {
    std::uint64_t key = 0;
    FileId file = 0;
  };

  bool empty() const noexcept { return heap_.empty(); }
  std::size_t size() const noexcept { return heap_.size(); }
  const Entry& top() const noexcept { return heap_.front(); }
  bool contains(FileId file) const noexcept { return file < position_.size() && position_[file] != kAbsent; }
  std::uint64_t key(FileId file) const noexcept { return heap_[position_[file]].key; }

  /// Adds `file` with `key`, or lowers its key to `key` if that is lower.
  void lower(FileId file, std::uint64_t key) {
    if (file >= position_.size()) position_.resize(static_cast<std::size_t>(file) + 1, kAbsent);
    if (position_[file] == kAbsent) {
      heap_.push_back({key, file});
      position_[file] = static_cast<std::uint32_t>(heap_.size() - 1);
      sift_up(heap_.size() - 1);
    } else if (key < heap_[position_[file]].key) {
      heap_[position_[file]].key = key;
      sift_up(position_[file]);
    }
  }
  /// Raises the top's key to `key`.
  void raise_top(std::uint64_t key) {
    PC_ASSERT(!heap_.empty() && key > heap_.front().key);
    heap_.front().key = key;
    sift_down(0);
  }
  void pop() {
    PC_ASSERT(!heap_.empty());
    position_[heap_.front().file] = kAbsent;
    const Entry last = heap_.back();
    heap_.pop_back();
    if (heap_.empty()) return;
    heap_.front() = last;
    position_[last.file] = 0;
    sift_down(0);
  }

  /// Throws InvariantError if the heap order or the positions are broken.
  void check() const {
    std::size_t present = 0;
    for (std::size_t i = 0; i < heap_.size(); ++i) {
      PC_ASSERT_MSG(i == 0 || heap_[(i - 1) / 2].key <= heap_[i].key, "file heap out of order");
      PC_ASSERT_MSG(contains(heap_[i].file) && position_[heap_[i].file] == i, "file heap position wrong");
    }
    for (std::uint32_t p : position_) present += p != kAbsent;
    PC_ASSERT_MSG(present == heap_.size(), "file heap holds a position for a file not in it");
  }

 private:
  static constexpr std::uint32_t kAbsent = std::numeric_limits<std::uint32_t>::max();

  void sift_up(std::size_t i) {
    const Entry moving = heap_[i];
    while (i > 0) {
      const std::size_t parent = (i - 1) / 2;
      if (heap_[parent].key <= moving.key) break;
      put(i, heap_[parent]);
      i = parent;
    }
    put(i, moving);
  }
  void sift_down(std::size_t i) {
    const Entry moving = heap_[i];
    const std::size_t n = heap_.size();
    for (;;) {
      std::size_t child = 2 * i + 1;
      if (child >= n) break;
      if (child + 1 < n && heap_[child + 1].key < heap_[child].key) ++child;
      if (moving.key <= heap_[child].key) break;
      put(i, heap_[child]);
      i = child;
    }
    put(i, moving);
  }
  void put(std::size_t i, const Entry& entry) {
    heap_[i] = entry;
    position_[entry.file] = static_cast<std::uint32_t>(i);
  }

  std::vector<Entry> heap_;
  std::vector<std::uint32_t> position_;  // by file: its index in heap_, or kAbsent
};

}  // namespace pagecache::cache
