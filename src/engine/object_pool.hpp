#pragma once
// ObjectPool<T>: recycles objects of one type through a free list, so that hot paths (events,
// flows, blocks) do not allocate once the pool has grown to its peak. Objects are reset to T()
// when taken. Addresses are stable for the pool's lifetime.
//
// Storage comes in chunks of doubling size, each left raw until its objects are first taken,
// so that memory beyond the peak is never written (nor faulted in by the kernel).

#include <cstddef>
#include <new>
#include <vector>

namespace pagecache::detail {

template <class T>
class ObjectPool {
 public:
  ObjectPool() = default;
  ObjectPool(const ObjectPool&) = delete;
  ObjectPool& operator=(const ObjectPool&) = delete;
  ~ObjectPool() {
    for (Chunk& chunk : chunks_) {
      for (std::size_t i = 0; i < chunk.constructed; ++i) chunk.objects[i].~T();
      ::operator delete(static_cast<void*>(chunk.objects), std::align_val_t{alignof(T)});
    }
  }

  T* take() {
    const bool recycled = !free_.empty();
    T* object = take_as_left();
    if (recycled) *object = T();
    return object;
  }
  /// As take(), but a recycled object comes as its last user left it (a fresh one as T()): for
  /// a caller that sets every field it reads, sparing the writes of a reset.
  T* take_as_left() {
    if (free_.empty()) return take_fresh();
    T* object = free_.back();
    free_.pop_back();
    ++in_use_;
    return object;
  }
  void give_back(T* object) noexcept {
    free_.push_back(object);  // capacity reserved in grow(): never reallocates here
    --in_use_;
  }
  std::size_t in_use() const noexcept { return in_use_; }

 private:
  struct Chunk {
    T* objects;
    std::size_t capacity;
    std::size_t constructed;
  };

  // Out of line: only while the pool grows to its peak.
  [[gnu::noinline]] T* take_fresh() {
    if (chunks_.empty() || chunks_.back().constructed == chunks_.back().capacity) grow();
    Chunk& chunk = chunks_.back();
    T* object = ::new (static_cast<void*>(chunk.objects + chunk.constructed)) T();
    ++chunk.constructed;
    ++in_use_;
    return object;
  }

  void grow() {
    const std::size_t size = chunks_.empty() ? 64 : chunks_.back().capacity * 2;
    free_.reserve(capacity_ + size);  // address space only: untouched until used
    chunks_.reserve(chunks_.size() + 1);
    auto* objects = static_cast<T*>(::operator new(size * sizeof(T), std::align_val_t{alignof(T)}));
    chunks_.push_back({objects, size, 0});
    capacity_ += size;
  }

  std::vector<Chunk> chunks_;
  std::vector<T*> free_;
  std::size_t capacity_ = 0;
  std::size_t in_use_ = 0;
};

}  // namespace pagecache::detail
