#pragma once
// Timer: a cancellable, re-armable alarm that runs a callback inside the event loop.
//
// Arming an armed timer moves it. The callback is stored once, at construction; firing
// allocates nothing. A timer is disarmed when it fires, when cancelled, and when destroyed.

#include <pagecache/simulator.hpp>

#include <functional>

namespace pagecache {

class Timer {
 public:
  Timer(Simulator& sim, std::function<void()> on_fire);
  Timer(const Timer&) = delete;
  Timer& operator=(const Timer&) = delete;
  ~Timer();

  /// Fires at absolute time `time` (>= now()).
  void arm_at(double time);
  /// Fires `delay` seconds from now (delay >= 0).
  void arm_in(double delay);
  /// Disarms the timer. Returns false if it was not armed.
  bool cancel() noexcept;
  bool armed() const noexcept { return static_cast<bool>(event_); }
  /// When an armed timer will fire.
  double due() const noexcept;

 private:
  static void fire(void* self);
  Simulator* sim_;
  std::function<void()> on_fire_;
  EventHandle event_;
};

}  // namespace pagecache
