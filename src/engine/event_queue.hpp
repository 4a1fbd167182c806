#pragma once
// EventQueue: the simulator's agenda, an indexed 4-ary heap of pooled event nodes ordered by
// (time, sequence). Nodes come from a pool and the heap is one array, so scheduling does not
// allocate once both have grown to the peak number of pending events.

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
  void erase(QueuedEvent* node) noexcept;
  void update(QueuedEvent* node, double time);
  /// Removes the earliest event and returns it; its node is recycled before the callback runs.
  Fired pop() noexcept;
  bool empty() const noexcept { return heap_.empty(); }
  std::size_t size() const noexcept { return heap_.size(); }
  double top_time() const noexcept { return heap_.top().time; }
  void clear() noexcept;

 private:
  EventHeap heap_;
  std::uint64_t next_sequence_ = 0;
  ObjectPool<QueuedEvent> nodes_;
};

}  // namespace pagecache::detail
