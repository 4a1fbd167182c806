#include "engine/event_queue.hpp"

namespace pagecache::detail {

QueuedEvent* EventQueue::push(double time, EventCallback callback, void* context) {
  QueuedEvent* node = nodes_.take();
  node->time = time;
  node->callback = callback;
  node->context = context;
  heap_.push({time, next_sequence_++, node});
  return node;
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
  QueuedEvent* node = heap_.top().event;
  heap_.pop();
  Fired fired{node->time, node->callback, node->context};
  nodes_.give_back(node);
  return fired;
}

void EventQueue::clear() noexcept {
  for (const QueueEntry& entry : heap_) nodes_.give_back(entry.event);
  heap_.clear();
}

}  // namespace pagecache::detail
