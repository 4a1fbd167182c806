#include <pagecache/event.hpp>

#include <pagecache/error.hpp>

#include <fmt/format.h>

namespace pagecache {

namespace detail {

EventWaiter::~EventWaiter() {
  unlink();
  if (sim_ != nullptr) {
    sim_->cancel(timeout_event_);
    sim_->cancel(wake_event_);
  }
}

bool EventWaiter::ready() noexcept {
  // An event already triggered completes the wait without suspending, as triggered.
  if (event_ != nullptr && event_->triggered_) triggered_ = true;
  return triggered_;
}

void EventWaiter::suspend(std::coroutine_handle<> waiting) {
  waiting_ = waiting;
  sim_ = event_->sim_;
  prev_ = event_->tail_;
  next_ = nullptr;
  if (event_->tail_ != nullptr) event_->tail_->next_ = this;
  else event_->head_ = this;
  event_->tail_ = this;
  linked_ = true;
  ++event_->waiting_;
  if (timeout_ >= 0.0) timeout_event_ = sim_->schedule_at(sim_->now() + timeout_, &on_timeout, this);
}

void EventWaiter::unlink() noexcept {
  if (!linked_) return;
  if (prev_ != nullptr) prev_->next_ = next_;
  else event_->head_ = next_;
  if (next_ != nullptr) next_->prev_ = prev_;
  else event_->tail_ = prev_;
  prev_ = next_ = nullptr;
  linked_ = false;
  --event_->waiting_;
}

void EventWaiter::on_timeout(void* self) {
  auto* waiter = static_cast<EventWaiter*>(self);
  waiter->timeout_event_.reset();
  waiter->unlink();
  waiter->waiting_.resume();
}

void EventWaiter::on_wake(void* self) {
  auto* waiter = static_cast<EventWaiter*>(self);
  waiter->wake_event_.reset();
  waiter->waiting_.resume();
}

}  // namespace detail

Event::~Event() {
  while (head_ != nullptr) {
    detail::EventWaiter* waiter = head_;
    waiter->unlink();
    waiter->event_ = nullptr;
  }
}

void Event::trigger() {
  if (triggered_) return;
  triggered_ = true;
  while (head_ != nullptr) {
    detail::EventWaiter* waiter = head_;
    waiter->unlink();
    waiter->triggered_ = true;
    sim_->cancel(waiter->timeout_event_);
    waiter->wake_event_ = sim_->schedule_at(sim_->now(), &detail::EventWaiter::on_wake, waiter);
  }
}

Event::TimedWaitAwaiter Event::wait_for(double timeout) {
  if (!(timeout >= 0.0)) throw SimulationError(fmt::format("wait_for: negative timeout {} s", timeout));
  return TimedWaitAwaiter(*this, timeout);
}

}  // namespace pagecache
