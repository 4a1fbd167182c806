#pragma once
// ObjectPool<T>: recycles objects of one type through a free list, so that hot paths (events,
// flows) do not allocate once the pool has grown to its peak. Objects are reset to T() when
// taken. Addresses are stable for the pool's lifetime.

#include <cstddef>
#include <memory>
#include <vector>

namespace pagecache::detail {

template <class T>
class ObjectPool {
 public:
  ObjectPool() = default;
  ObjectPool(const ObjectPool&) = delete;
  ObjectPool& operator=(const ObjectPool&) = delete;

  T* take() {
    if (free_.empty()) grow();
    T* object = free_.back();
    free_.pop_back();
    *object = T();
    ++in_use_;
    return object;
  }
  void give_back(T* object) noexcept {
    free_.push_back(object);  // capacity reserved in grow(): never reallocates here
    --in_use_;
  }
  std::size_t in_use() const noexcept { return in_use_; }

 private:
  void grow() {
    auto chunk = std::make_unique<T[]>(next_chunk_);
    free_.reserve(capacity_ + next_chunk_);
    for (std::size_t i = next_chunk_; i-- > 0;) free_.push_back(&chunk[i]);
    capacity_ += next_chunk_;
    next_chunk_ *= 2;
    chunks_.push_back(std::move(chunk));
  }

  std::vector<std::unique_ptr<T[]>> chunks_;
  std::vector<T*> free_;
  std::size_t capacity_ = 0;
  std::size_t next_chunk_ = 64;
  std::size_t in_use_ = 0;
};

}  // namespace pagecache::detail
