#pragma once
// EventQueue: the simulator's agenda, events ordered by (time, sequence). Events for later
// times are pooled nodes in an indexed 4-ary heap (one array; they can be cancelled and
// moved). Wake-ups for the current time, half of all events (every flow that ends, every
// event triggered wakes its process at now()), cannot be cancelled and come out in the order
// they were made: they wait in a ring buffer instead, taken before any heap event of a later
// sequence number. Nothing allocates once both have grown to their peaks.

#include <pagecache/simulator.hpp>

#include "engine/indexed_heap.hpp"
#include "engine/object_pool.hpp"

#include <cstdint>
#include <memory>
#include <vector>

namespace pagecache::detail {

struct QueuedEvent;

// The heap holds the ordering key beside the pointer to the event, so that comparisons stay
// within the heap's own array.
struct QueueEntry {
  double time;
  std::uint64_t sequence;
  QueuedEvent* event;
};

struct RunsFirst {
  bool operator()(const QueueEntry& a, const QueueEntry& b) const noexcept {
    if (a.time != b.time) return a.time < b.time;
    return a.sequence < b.sequence;
  }
};

struct QueuedEvent {
  double time = 0.0;
  EventCallback callback = nullptr;
  void* context = nullptr;
  std::uint32_t heap_index = 0;
};

struct PlaceEvent {
  void operator()(const QueueEntry& entry, std::uint32_t index) const noexcept { entry.event->heap_index = index; }
};

using EventHeap = IndexedHeap<QueueEntry, RunsFirst, PlaceEvent>;

class EventQueue {
 public:
  struct Fired {
    double time;
    EventCallback callback;
    void* context;
  };

  EventQueue() = default;
  EventQueue(const EventQueue&) = delete;
  EventQueue& operator=(const EventQueue&) = delete;

  QueuedEvent* push(double time, EventCallback callback, void* context);
  /// A wake-up at `now`, the current time (never cancelled).
  void push_now(double now, EventCallback callback, void* context);
  void erase(QueuedEvent* node) noexcept;
  void update(QueuedEvent* node, double time);
  /// Removes the earliest event and returns it; its node is recycled before the callback runs.
  Fired pop() noexcept;
  bool empty() const noexcept { return heap_.empty() && ring_count_ == 0; }
  std::size_t size() const noexcept { return heap_.size() + ring_count_; }
  double top_time() const noexcept { return ring_count_ > 0 ? ring_[ring_head_].time : heap_.top().time; }
  void clear() noexcept;

 private:
  struct Wake {
    double time;
    std::uint64_t sequence;
    EventCallback callback;
    void* context;
  };
  bool ring_first() const noexcept;

  EventHeap heap_;
  std::vector<Wake> ring_;  // capacity a power of two
  std::size_t ring_head_ = 0;
  std::size_t ring_count_ = 0;
  std::uint64_t next_sequence_ = 0;
  ObjectPool<QueuedEvent> nodes_;
};

}  // namespace pagecache::detail
