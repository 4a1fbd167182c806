#pragma once
// Simulator: the discrete-event kernel. It owns the simulated clock (seconds, double) and the
// event queue, and runs processes: Task<void> coroutines started with spawn().
//
// Events are ordered by (time, sequence number): events at equal times run in the order they
// were scheduled, so a run is deterministic. Every wake-up of a process goes through the queue
// (never an inline resume), which keeps the stack depth bounded.
//
// There is no global state: several Simulators can live in one process. An exception that
// escapes a process stops run() and is rethrown from it. Destroying a Simulator destroys the
// processes still suspended in it; objects they wait on (devices, events, timers) should be
// declared after the Simulator they use, or at least outlive its run.

#include <pagecache/error.hpp>
#include <pagecache/task.hpp>

#include <coroutine>
#include <cstdint>
#include <memory>

namespace pagecache {

namespace detail {
struct QueuedEvent;
struct SimulatorCore;
}

/// A plain callback run by the event loop: no allocation, no type erasure per event.
using EventCallback = void (*)(void* context);

/// A scheduled event, as returned by Simulator::schedule_at. Owners keep it while the event is
/// pending and must drop it when the event fires or is cancelled: it is then invalid.
class EventHandle {
 public:
  EventHandle() noexcept = default;
  explicit operator bool() const noexcept { return node_ != nullptr; }
  void reset() noexcept { node_ = nullptr; }

 private:
  friend class Simulator;
  explicit EventHandle(detail::QueuedEvent* node) noexcept : node_(node) {}
  detail::QueuedEvent* node_ = nullptr;
};

class Simulator;

/// Awaitable returned by Simulator::sleep / sleep_until. Destroying a suspended sleeper (its
/// process being torn down) cancels its wake-up.
class SleepAwaiter {
 public:
  SleepAwaiter(Simulator& sim, double wake_time) noexcept : sim_(&sim), wake_time_(wake_time) {}
  SleepAwaiter(const SleepAwaiter&) = delete;
  SleepAwaiter& operator=(const SleepAwaiter&) = delete;
  ~SleepAwaiter();

  bool await_ready() const noexcept { return false; }
  void await_suspend(std::coroutine_handle<> waiting);
  void await_resume() const noexcept {}

 private:
  static void fire(void* self);
  Simulator* sim_;
  double wake_time_;
  std::coroutine_handle<> waiting_;
  EventHandle event_;
};

class Simulator {
 public:
  Simulator();
  ~Simulator();
  Simulator(const Simulator&) = delete;
  Simulator& operator=(const Simulator&) = delete;

  /// Current simulated time in seconds.
  double now() const noexcept { return now_; }

  /// Starts `process` as a concurrent process: it begins at now(), after the events already
  /// scheduled for now(). The simulator owns it until it completes.
  void spawn(Task<void> process);

  /// Runs events until none is left. Rethrows the first exception that escaped a process or
  /// an event callback; the simulator can be run again afterwards.
  void run();

  /// Runs every event scheduled at or before `time`, then advances the clock to `time`.
  void run_until(double time);

  /// Runs the next event. Returns false if the queue was empty.
  bool step();

  /// Number of events run so far.
  std::uint64_t events_processed() const noexcept { return events_processed_; }
  /// Number of events waiting in the queue.
  std::size_t pending_events() const noexcept;
  /// Number of spawned processes that have not completed.
  std::size_t live_processes() const noexcept;

  /// Suspends the awaiting process for `delay` seconds (>= 0; 0 yields to the events already
  /// scheduled for now()).
  [[nodiscard]] SleepAwaiter sleep(double delay);
  /// Suspends the awaiting process until absolute time `time` (>= now()).
  [[nodiscard]] SleepAwaiter sleep_until(double time);

  // --- Low-level scheduling, for devices, timers and awaitables ---------------------------

  /// Schedules `callback(context)` at absolute time `time` (>= now()).
  EventHandle schedule_at(double time, EventCallback callback, void* context);
  /// Cancels a pending event and resets the handle. Returns false if the handle was empty.
  bool cancel(EventHandle& event) noexcept;
  /// Moves a pending event to `time` (>= now()); it is ordered as if scheduled just now.
  void reschedule(const EventHandle& event, double time);
  /// Time at which a pending event is due.
  double due(const EventHandle& event) const noexcept;
  /// Resumes `coroutine` at now(), after the events already scheduled for now().
  void wake(std::coroutine_handle<> coroutine);

 private:
  void check_time(double time, const char* what) const;

  std::unique_ptr<detail::SimulatorCore> impl_;
  double now_ = 0.0;
  std::uint64_t events_processed_ = 0;
};

}  // namespace pagecache
