#pragma once
// EventQueue: the simulator's agenda, events ordered by (time, sequence), from sources each
// already in that order, merged at pop:
//  - wake-ups for the current time (every flow that ends, every event triggered wakes its
//    process at now(): half of all events): never cancelled, they wait in a ring buffer;
//  - a few runs of later events, each made in non-decreasing time order: the completions of
//    many equal operations started by processes in step, the sleeps of equal computations,
//    a periodic timer, each come due in the order they were scheduled. An event joins the run
//    whose last time is the latest not after its own, so that runs stay tight. Appending to a
//    run and taking its front are O(1); a cancelled member leaves a tombstone that is skipped;
//  - every event that fits no run: pooled nodes in an indexed 4-ary heap (one array; they can
//    be cancelled and moved in O(log n)).
// Most events skip the heap, whose pops move entries across memory with many applications.
// Nothing allocates once the buffers have grown to their peaks. pop() prefetches the state of
// events a few places behind the front of the ring and of its run (see kAhead).

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

// The agenda's order: by time, then by when the event was made.
constexpr bool runs_before(double time, std::uint64_t sequence, double other_time, std::uint64_t other_sequence) noexcept {
  return time < other_time || (time == other_time && sequence < other_sequence);
}

struct RunsFirst {
  bool operator()(const QueueEntry& a, const QueueEntry& b) const noexcept {
    return runs_before(a.time, a.sequence, b.time, b.sequence);
  }
};

inline constexpr std::uint8_t kInHeap = 0xff;

struct QueuedEvent {
  double time = 0.0;
  EventCallback callback = nullptr;
  void* context = nullptr;
  std::uint32_t heap_index = 0;  // where it is: its heap index, or its slot in its run
  std::uint8_t run = 0;          // its run, or kInHeap
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
  bool empty() const noexcept { return heap_.empty() && ring_count_ == 0 && runs_used_ == 0; }
  std::size_t size() const noexcept { return heap_.size() + ring_count_ + run_live_; }
  /// The time of the earliest event; the queue must not be empty.
  double top_time() const noexcept;
  void clear() noexcept;

 private:
  struct Wake {
    double time;
    std::uint64_t sequence;
    EventCallback callback;
    void* context;
  };
  // A run: a circular buffer (capacity a power of two) of entries in (time, sequence) order;
  // event == nullptr marks a cancelled one. The head is never a tombstone. An entry carries
  // its callback too, so that running it does not read its node, made long ago and out of
  // cache with many processes in step (the node is only recycled). The keys of every
  // run's first and last entries are kept side by side (below), so that choosing a run for a
  // push or the earliest run at a pop reads a few cache lines only.
  struct RunEntry {
    double time;
    std::uint64_t sequence;
    QueuedEvent* event;
    EventCallback callback;
    void* context;
  };
  struct Run {
    std::vector<RunEntry> slots;
    std::size_t mask = 0;
    std::size_t head = 0;
    std::size_t count = 0;  // slots from the head, tombstones included
  };
  static constexpr std::uint8_t kRuns = 8;
  static constexpr std::uint8_t kRing = kInHeap - 1;  // first(): the ring comes first

  std::uint8_t first() const noexcept;
  std::uint8_t earliest_run() const noexcept;
  void place(QueuedEvent* node, std::uint64_t sequence);
  void append(std::uint8_t run, QueuedEvent* node, std::uint64_t sequence);
  void take_front(std::uint8_t run) noexcept;
  void drop_tombstones(std::uint8_t run) noexcept;
  void remove(QueuedEvent* node) noexcept;

  EventHeap heap_;
  Run runs_[kRuns];
  double run_front_time_[kRuns] = {};
  std::uint64_t run_front_sequence_[kRuns] = {};
  double run_back_time_[kRuns] = {};
  std::uint8_t runs_used_ = 0;  // bit r: run r has events
  // The run with the earliest front (kInHeap: none), recomputed only when that front moves.
  mutable std::uint8_t earliest_run_ = kInHeap;
  mutable bool earliest_known_ = true;
  std::size_t run_live_ = 0;  // live events in all runs
  std::vector<Wake> ring_;  // capacity a power of two
  std::size_t ring_head_ = 0;
  std::size_t ring_count_ = 0;
  std::uint64_t next_sequence_ = 0;
  ObjectPool<QueuedEvent> nodes_;
};

}  // namespace pagecache::detail
