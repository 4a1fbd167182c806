// Coroutine frames: every Task and process frame comes from here (TaskPromiseBase's operator
// new). A simulation creates and destroys a frame for every chunk it reads or writes, many
// levels deep; per-size free lists recycle them without malloc, and reuse frames still in cache.
//
// One pool per thread, no locking. Sizes are rounded up to 64 bytes; frames above 4 KiB go to
// the global allocator. Each free list keeps at most 1 MiB of frames until the thread ends,
// the rest goes back to the global allocator, where any size can reuse it.

#include <pagecache/task.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <new>

namespace pagecache::detail {

namespace {

constexpr std::size_t kGranule = 64;
constexpr std::size_t kLargest = 4096;
// Frames kept per size: enough for those a run frees and makes again at once, which with 10^4
// writers in step is more than 64 KiB of one size. Not each size's peak: peaks come at
// different times (10^5 applications reading, then writing), and keeping each would hold both.
constexpr std::size_t kKeptBytes = 1024 * 1024;

struct FreeFrame {
  FreeFrame* next;
};

class FramePool {
 public:
  ~FramePool() {
    for (FreeFrame*& head : free_) {
      while (head != nullptr) ::operator delete(std::exchange(head, head->next));
    }
    alive_ = false;
  }
  static bool alive() noexcept { return alive_; }

  void* allocate(std::size_t size) {
    const std::size_t slot = (size - 1) / kGranule;
    if (FreeFrame* frame = free_[slot]) {
      free_[slot] = frame->next;
      --count_[slot];
      return frame;
    }
    return ::operator new((slot + 1) * kGranule);
  }
  void release(void* frame, std::size_t size) noexcept {
    const std::size_t slot = (size - 1) / kGranule;
    if (count_[slot] >= kKeptBytes / ((slot + 1) * kGranule)) {
      ::operator delete(frame);
      return;
    }
    ++count_[slot];
    free_[slot] = new (frame) FreeFrame{free_[slot]};
  }

 private:
  std::array<FreeFrame*, kLargest / kGranule> free_{};
  std::array<std::uint32_t, kLargest / kGranule> count_{};
  static thread_local bool alive_;
};

thread_local bool FramePool::alive_ = true;
thread_local FramePool pool;

}  // namespace

void* allocate_frame(std::size_t size) {
  if (size == 0 || size > kLargest || !FramePool::alive()) return ::operator new(size);
  return pool.allocate(size);
}

void free_frame(void* frame, std::size_t size) noexcept {
  if (size == 0 || size > kLargest || !FramePool::alive()) {
    ::operator delete(frame);
    return;
  }
  pool.release(frame, size);
}

}  // namespace pagecache::detail
