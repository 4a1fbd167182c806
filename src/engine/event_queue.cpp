#include "engine/event_queue.hpp"

namespace pagecache::detail {

QueuedEvent* EventQueue::push(double time, EventCallback callback, void* context) {
  QueuedEvent* node = nodes_.take();
  node->time = time;
  node->callback = callback;
  node->context = context;
  node->handle = heap_.push({time, next_sequence_++, node});
  return node;
}

void EventQueue::erase(QueuedEvent* node) noexcept {
  heap_.erase(node->handle);
  nodes_.give_back(node);
}

void EventQueue::update(QueuedEvent* node, double time) {
  const bool runs_later = time >= node->time;  // the new sequence number is always larger
  node->time = time;
  if (runs_later) heap_.decrease(node->handle, {time, next_sequence_++, node});
  else heap_.increase(node->handle, {time, next_sequence_++, node});
}

EventQueue::Fired EventQueue::pop() noexcept {
  QueuedEvent* node = heap_.top().event;
  heap_.pop();
  Fired fired{node->time, node->callback, node->context};
  nodes_.give_back(node);
  return fired;
}

void EventQueue::clear() noexcept {
  while (!heap_.empty()) {
    QueuedEvent* node = heap_.top().event;
    heap_.pop();
    nodes_.give_back(node);
  }
}

}  // namespace pagecache::detail
