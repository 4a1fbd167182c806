#include "engine/event_queue.hpp"

#include <algorithm>

namespace pagecache::detail {

namespace {

// How many events ahead pop() prefetches what an event will touch first (its context, and for
// a run its node, recycled when it fires). With 10^5 processes in step, consecutive events
// belong to different processes whose state is out of cache; the runs and the ring know their
// next events long before they fire, so the misses can overlap instead of following one another.
constexpr std::size_t kAhead = 8;
constexpr std::size_t kLinesAhead = 4;

void prefetch_lines(const void* at) noexcept {
  const char* p = static_cast<const char*>(at);
  for (std::size_t i = 0; i < kLinesAhead; ++i) __builtin_prefetch(p + 64 * i, 1);
}

// Unrolls a circular buffer of `count` items from `head` into one twice the size.
template <class T>
void grow_circular(std::vector<T>& buffer, std::size_t& head, std::size_t count) {
  std::vector<T> bigger(std::max<std::size_t>(64, buffer.size() * 2));
  for (std::size_t i = 0; i < count; ++i) bigger[i] = buffer[(head + i) & (buffer.size() - 1)];
  buffer = std::move(bigger);
  head = 0;
}

}  // namespace

QueuedEvent* EventQueue::push(double time, EventCallback callback, void* context) {
  QueuedEvent* node = nodes_.take();
  node->time = time;
  node->callback = callback;
  node->context = context;
  place(node, next_sequence_++);
  return node;
}

// Into the run whose last event is the latest not after it, else into an empty run, else
// into the heap.
void EventQueue::place(QueuedEvent* node, std::uint64_t sequence) {
  std::uint8_t best = kInHeap;
  double best_time = 0.0;
  for (unsigned used = runs_used_; used != 0; used &= used - 1) {
    const auto r = static_cast<std::uint8_t>(__builtin_ctz(used));
    const double back = run_back_time_[r];
    if (back <= node->time && (best == kInHeap || back > best_time)) {
      best = r;
      best_time = back;
    }
  }
  if (best == kInHeap && runs_used_ != (1u << kRuns) - 1) best = static_cast<std::uint8_t>(__builtin_ctz(~unsigned{runs_used_}));
  if (best == kInHeap) {
    node->run = kInHeap;
    heap_.push({node->time, sequence, node});
  } else {
    append(best, node, sequence);
  }
}

void EventQueue::append(std::uint8_t r, QueuedEvent* node, std::uint64_t sequence) {
  Run& run = runs_[r];
  if (run.count == run.slots.size()) {
    grow_circular(run.slots, run.head, run.count);
    run.mask = run.slots.size() - 1;
    for (std::size_t i = 0; i < run.count; ++i) {
      if (run.slots[i].event != nullptr) run.slots[i].event->heap_index = static_cast<std::uint32_t>(i);
    }
  }
  const std::size_t slot = (run.head + run.count) & run.mask;
  run.slots[slot] = {node->time, sequence, node, node->callback, node->context};
  node->run = r;
  node->heap_index = static_cast<std::uint32_t>(slot);
  if (run.count++ == 0) {
    run_front_time_[r] = node->time;
    run_front_sequence_[r] = sequence;
    runs_used_ = static_cast<std::uint8_t>(runs_used_ | (1u << r));
    if (earliest_known_ && (earliest_run_ == kInHeap || node->time < run_front_time_[earliest_run_])) earliest_run_ = r;
  }
  run_back_time_[r] = node->time;
  ++run_live_;
}

void EventQueue::take_front(std::uint8_t r) noexcept {
  Run& run = runs_[r];
  run.head = (run.head + 1) & run.mask;
  --run.count;
  drop_tombstones(r);
}

// Keeps the head of run r live, and its key and the used bit current.
void EventQueue::drop_tombstones(std::uint8_t r) noexcept {
  if (r == earliest_run_) earliest_known_ = false;  // its front may have moved
  Run& run = runs_[r];
  while (run.count > 0 && run.slots[run.head].event == nullptr) {
    run.head = (run.head + 1) & run.mask;
    --run.count;
  }
  if (run.count == 0) {
    runs_used_ = static_cast<std::uint8_t>(runs_used_ & ~(1u << r));
  } else {
    run_front_time_[r] = run.slots[run.head].time;
    run_front_sequence_[r] = run.slots[run.head].sequence;
  }
}

void EventQueue::push_now(double now, EventCallback callback, void* context) {
  if (ring_count_ == ring_.size()) grow_circular(ring_, ring_head_, ring_count_);
  ring_[(ring_head_ + ring_count_) & (ring_.size() - 1)] = Wake{now, next_sequence_++, callback, context};
  ++ring_count_;
}

std::uint8_t EventQueue::earliest_run() const noexcept {
  if (!earliest_known_) {
    std::uint8_t best = kInHeap;
    for (unsigned used = runs_used_; used != 0; used &= used - 1) {
      const auto r = static_cast<std::uint8_t>(__builtin_ctz(used));
      if (best == kInHeap || runs_before(run_front_time_[r], run_front_sequence_[r], run_front_time_[best], run_front_sequence_[best])) {
        best = r;
      }
    }
    earliest_run_ = best;
    earliest_known_ = true;
  }
  return earliest_run_;
}

// The source of the earliest event: a run, the heap (kInHeap) or the ring (kRing).
std::uint8_t EventQueue::first() const noexcept {
  std::uint8_t best = kInHeap;
  double time = 0.0;
  std::uint64_t sequence = 0;
  bool any = !heap_.empty();
  if (any) {
    time = heap_.top().time;
    sequence = heap_.top().sequence;
  }
  if (const std::uint8_t r = earliest_run(); r != kInHeap) {
    if (!any || runs_before(run_front_time_[r], run_front_sequence_[r], time, sequence)) {
      best = r;
      time = run_front_time_[r];
      sequence = run_front_sequence_[r];
      any = true;
    }
  }
  if (ring_count_ > 0) {
    const Wake& wake = ring_[ring_head_];
    if (!any || runs_before(wake.time, wake.sequence, time, sequence)) best = kRing;
  }
  return best;
}

double EventQueue::top_time() const noexcept {
  const std::uint8_t source = first();
  if (source == kRing) return ring_[ring_head_].time;
  if (source == kInHeap) return heap_.top().time;
  return run_front_time_[source];
}

// Takes a node out of its run or the heap, without recycling it.
void EventQueue::remove(QueuedEvent* node) noexcept {
  if (node->run == kInHeap) {
    heap_.erase(node->heap_index);
    return;
  }
  runs_[node->run].slots[node->heap_index].event = nullptr;
  --run_live_;
  drop_tombstones(node->run);
}

void EventQueue::erase(QueuedEvent* node) noexcept {
  remove(node);
  nodes_.give_back(node);
}

void EventQueue::update(QueuedEvent* node, double time) {
  remove(node);
  node->time = time;
  place(node, next_sequence_++);
}

EventQueue::Fired EventQueue::pop() noexcept {
  const std::uint8_t source = first();
  if (source == kRing) {
    const Wake& wake = ring_[ring_head_];
    const Fired fired{wake.time, wake.callback, wake.context};
    if (ring_count_ > kAhead) prefetch_lines(ring_[(ring_head_ + kAhead) & (ring_.size() - 1)].context);
    ring_head_ = (ring_head_ + 1) & (ring_.size() - 1);
    --ring_count_;
    return fired;
  }
  if (source == kInHeap) {
    QueuedEvent* node = heap_.top().event;
    heap_.pop();
    const Fired fired{node->time, node->callback, node->context};
    nodes_.give_back(node);
    return fired;
  }
  const Run& run = runs_[source];
  const RunEntry& entry = run.slots[run.head];
  const Fired fired{entry.time, entry.callback, entry.context};
  if (run.count > kAhead) {
    const RunEntry& ahead = run.slots[(run.head + kAhead) & run.mask];
    prefetch_lines(ahead.context);
    __builtin_prefetch(ahead.event, 1);
  }
  nodes_.give_back(entry.event);
  --run_live_;
  take_front(source);
  return fired;
}

void EventQueue::clear() noexcept {
  for (const QueueEntry& entry : heap_) nodes_.give_back(entry.event);
  heap_.clear();
  for (Run& run : runs_) {
    for (std::size_t i = 0; i < run.count; ++i) {
      QueuedEvent* node = run.slots[(run.head + i) & run.mask].event;
      if (node != nullptr) nodes_.give_back(node);
    }
    run.head = 0;
    run.count = 0;
  }
  runs_used_ = 0;
  earliest_run_ = kInHeap;
  earliest_known_ = true;
  run_live_ = 0;
  ring_head_ = 0;
  ring_count_ = 0;
}

}  // namespace pagecache::detail
