#pragma once
// Event: a one-shot signal that processes wait on.
//
// `co_await event.wait()` suspends until trigger(); waiters resume at the trigger time, in the
// order they started waiting, each through the event queue. Once triggered, an Event stays
// triggered: later waits complete at once. `co_await event.wait_for(timeout)` also resumes
// after `timeout` seconds and tells which came first.

#include <pagecache/simulator.hpp>

#include <coroutine>

namespace pagecache {

class Event;

namespace detail {
// A suspended waiter, linked into its Event's FIFO list. Lives in the waiting coroutine's frame.
class EventWaiter {
 public:
  EventWaiter(Event& event, double timeout) noexcept : event_(&event), timeout_(timeout) {}
  EventWaiter(const EventWaiter&) = delete;
  EventWaiter& operator=(const EventWaiter&) = delete;
  ~EventWaiter();

 protected:
  bool ready() noexcept;
  void suspend(std::coroutine_handle<> waiting);
  bool triggered() const noexcept { return triggered_; }

 private:
  friend class pagecache::Event;
  static void on_timeout(void* self);
  static void on_wake(void* self);
  void unlink() noexcept;

  Event* event_;
  double timeout_;  // < 0: none
  EventWaiter* prev_ = nullptr;
  EventWaiter* next_ = nullptr;
  bool linked_ = false;
  bool triggered_ = false;
  std::coroutine_handle<> waiting_;
  Simulator* sim_ = nullptr;
  EventHandle timeout_event_;
  EventHandle wake_event_;
};
}  // namespace detail

class Event {
 public:
  explicit Event(Simulator& sim) noexcept : sim_(&sim) {}
  Event(const Event&) = delete;
  Event& operator=(const Event&) = delete;
  /// Waiters still suspended on a destroyed Event are never resumed.
  ~Event();

  /// Wakes every waiter at now(). Triggering twice has no further effect.
  void trigger();
  bool triggered() const noexcept { return triggered_; }
  /// Number of processes currently suspended on this event.
  std::size_t waiting() const noexcept { return waiting_; }

  class WaitAwaiter : public detail::EventWaiter {
   public:
    explicit WaitAwaiter(Event& event) noexcept : EventWaiter(event, -1.0) {}
    bool await_ready() noexcept { return ready(); }
    void await_suspend(std::coroutine_handle<> waiting) { suspend(waiting); }
    void await_resume() const noexcept {}
  };

  class TimedWaitAwaiter : public detail::EventWaiter {
   public:
    TimedWaitAwaiter(Event& event, double timeout) noexcept : EventWaiter(event, timeout) {}
    bool await_ready() noexcept { return ready(); }
    void await_suspend(std::coroutine_handle<> waiting) { suspend(waiting); }
    /// True if the event was triggered, false if the timeout expired first.
    bool await_resume() const noexcept { return triggered(); }
  };

  [[nodiscard]] WaitAwaiter wait() noexcept { return WaitAwaiter(*this); }
  /// Waits at most `timeout` seconds (>= 0).
  [[nodiscard]] TimedWaitAwaiter wait_for(double timeout);

 private:
  friend class detail::EventWaiter;
  Simulator* sim_;
  bool triggered_ = false;
  std::size_t waiting_ = 0;
  detail::EventWaiter* head_ = nullptr;
  detail::EventWaiter* tail_ = nullptr;
};

}  // namespace pagecache
