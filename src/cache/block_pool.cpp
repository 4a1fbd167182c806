#include "cache/block_pool.hpp"

#include <pagecache/error.hpp>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <type_traits>
#include <utility>

namespace pagecache::cache {

namespace {

static_assert(std::is_trivially_copyable_v<Block>, "blocks are moved by realloc");

// The array a pool of this thread left, for the next one (see BlockPool). One per thread, no
// locking; pools destroyed after it (thread_local destruction order) free their arrays.
constexpr std::size_t kKeptBytes = std::size_t{16} << 20;

class KeptArray {
 public:
  ~KeptArray() {
    std::free(raw_);
    alive_ = false;
  }
  static bool alive() noexcept { return alive_; }
  /// Takes the array kept, if any: its allocation and its capacity in blocks.
  std::pair<void*, std::size_t> take() noexcept { return {std::exchange(raw_, nullptr), std::exchange(capacity_, 0)}; }
  /// Keeps the larger of the two arrays, up to kKeptBytes, and frees the other.
  void offer(void* raw, std::size_t capacity) noexcept {
    if (capacity * sizeof(Block) > kKeptBytes || capacity < capacity_) {
      std::free(raw);
      return;
    }
    std::free(raw_);
    raw_ = raw;
    capacity_ = capacity;
  }

 private:
  void* raw_ = nullptr;
  std::size_t capacity_ = 0;
  static thread_local bool alive_;
};

thread_local bool KeptArray::alive_ = true;
thread_local KeptArray kept;

Block* first_aligned(void* raw) noexcept {
  const auto at = reinterpret_cast<std::uintptr_t>(raw);
  return reinterpret_cast<Block*>(static_cast<char*>(raw) + (alignof(Block) - at % alignof(Block)) % alignof(Block));
}

}  // namespace

BlockPool::~BlockPool() {
  if (KeptArray::alive()) kept.offer(raw_, capacity_);
  else std::free(raw_);
}

void BlockPool::grow() {
  if (raw_ == nullptr && KeptArray::alive()) {
    const auto [raw, capacity] = kept.take();
    if (raw != nullptr) {
      free_.reserve(capacity);
      raw_ = raw;
      blocks_ = first_aligned(raw);
      capacity_ = capacity;
      return;
    }
  }
  // The last id is kNoBlock's predecessor.
  if (capacity_ == kNoBlock) throw SimulationError("the page cache holds too many blocks (2^32 - 1)");
  const std::size_t capacity = capacity_ == 0 ? 64 : std::min<std::size_t>(2 * capacity_, kNoBlock);
  free_.reserve(capacity);
  const std::size_t offset = raw_ == nullptr ? 0 : static_cast<std::size_t>(reinterpret_cast<char*>(blocks_) - static_cast<char*>(raw_));
  void* raw = std::realloc(raw_, capacity * sizeof(Block) + alignof(Block));
  if (raw == nullptr) throw std::bad_alloc();
  // The blocks are where they were in the allocation, which may not be aligned as before.
  Block* aligned = first_aligned(raw);
  void* moved = static_cast<char*>(raw) + offset;
  if (static_cast<void*>(aligned) != moved) std::memmove(static_cast<void*>(aligned), moved, fresh_ * sizeof(Block));
  raw_ = raw;
  blocks_ = aligned;
  capacity_ = capacity;
}

}  // namespace pagecache::cache
