#include "engine/event_queue.hpp"

#include <algorithm>

namespace pagecache::detail {

QueuedEvent* EventQueue::push(double time, EventCallback callback, void* context) {
  QueuedEvent* node = nodes_.take();
  node->time = time;
  node->callback = callback;
  node->context = context;
  heap_.push({time, next_sequence_++, node});
  return node;
}

void EventQueue::push_now(double now, EventCallback callback, void* context) {
  if (ring_count_ == ring_.size()) {
    // Full: unroll into a buffer twice the size.
    std::vector<Wake> bigger(std::max<std::size_t>(64, ring_.size() * 2));
    for (std::size_t i = 0; i < ring_count_; ++i) bigger[i] = ring_[(ring_head_ + i) & (ring_.size() - 1)];
    ring_ = std::move(bigger);
    ring_head_ = 0;
  }
  ring_[(ring_head_ + ring_count_) & (ring_.size() - 1)] = Wake{now, next_sequence_++, callback, context};
  ++ring_count_;
}

bool EventQueue::ring_first() const noexcept {
  if (ring_count_ == 0) return false;
  if (heap_.empty()) return true;
  const Wake& wake = ring_[ring_head_];
  return RunsFirst{}({wake.time, wake.sequence, nullptr}, heap_.top());
}

void EventQueue::erase(QueuedEvent* node) noexcept {
  heap_.erase(node->heap_index);
  nodes_.give_back(node);
}

void EventQueue::update(QueuedEvent* node, double time) {
  node->time = time;
  heap_.replace(node->heap_index, {time, next_sequence_++, node});
}

EventQueue::Fired EventQueue::pop() noexcept {
  if (ring_first()) {
    const Wake& wake = ring_[ring_head_];
    const Fired fired{wake.time, wake.callback, wake.context};
    ring_head_ = (ring_head_ + 1) & (ring_.size() - 1);
    --ring_count_;
    return fired;
  }
  QueuedEvent* node = heap_.top().event;
  heap_.pop();
  Fired fired{node->time, node->callback, node->context};
  nodes_.give_back(node);
  return fired;
}

void EventQueue::clear() noexcept {
  for (const QueueEntry& entry : heap_) nodes_.give_back(entry.event);
  heap_.clear();
  ring_head_ = 0;
  ring_count_ = 0;
}

}  // namespace pagecache::detail
