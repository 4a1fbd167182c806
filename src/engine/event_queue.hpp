#pragma once
// EventQueue: the simulator's agenda, a Boost pairing heap of pooled event nodes ordered by
// (time, sequence). Nodes come from a pool, so scheduling does not allocate its node once the
// pool has grown to the peak number of pending events.

#include <pagecache/simulator.hpp>

#include "engine/object_pool.hpp"

#include <boost/heap/pairing_heap.hpp>

#include <cstdint>
#include <memory>
#include <vector>

namespace pagecache::detail {

struct QueuedEvent;

// Boost heaps are max-heaps: "less" here means "runs later".
struct RunsLater {
  bool operator()(const QueuedEvent* a, const QueuedEvent* b) const noexcept;
};

using EventHeap = boost::heap::pairing_heap<QueuedEvent*, boost::heap::compare<RunsLater>>;

struct QueuedEvent {
  double time = 0.0;
  std::uint64_t sequence = 0;
  EventCallback callback = nullptr;
  void* context = nullptr;
  EventHeap::handle_type handle;
};

inline bool RunsLater::operator()(const QueuedEvent* a, const QueuedEvent* b) const noexcept {
  if (a->time != b->time) return a->time > b->time;
  return a->sequence > b->sequence;
}

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
  double top_time() const noexcept { return heap_.top()->time; }
  void clear() noexcept;

 private:
  EventHeap heap_;
  std::uint64_t next_sequence_ = 0;
  ObjectPool<QueuedEvent> nodes_;
};

}  // namespace pagecache::detail
