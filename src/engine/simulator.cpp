#include <pagecache/simulator.hpp>

#include "engine/event_queue.hpp"

#include <fmt/format.h>

#include <cmath>
#include <exception>

namespace pagecache {

namespace {

struct ProcessPromise;

// The coroutine that owns a spawned Task: it awaits it, records an escaping exception in the
// simulator, and destroys itself when done. Live processes are linked in a list so that the
// simulator can destroy those still suspended when it is itself destroyed.
struct Process {
  using promise_type = ProcessPromise;
  std::coroutine_handle<ProcessPromise> handle;
};

}  // namespace

namespace detail {

struct SimulatorCore {
  detail::EventQueue queue;
  std::exception_ptr failure;
  ProcessPromise* processes = nullptr;  // intrusive list of live processes
  std::size_t live_processes = 0;

  void rethrow_failure() {
    if (failure) std::rethrow_exception(std::exchange(failure, nullptr));
  }
};

}  // namespace detail

namespace {

struct ProcessPromise {
  static void* operator new(std::size_t size) { return detail::allocate_frame(size); }
  static void operator delete(void* frame, std::size_t size) noexcept { detail::free_frame(frame, size); }

  ProcessPromise(detail::SimulatorCore& impl, Task<void>&) noexcept : impl_(&impl) {
    next_ = impl.processes;
    if (next_ != nullptr) next_->prev_ = this;
    impl.processes = this;
    ++impl.live_processes;
  }
  ~ProcessPromise() {
    if (prev_ != nullptr) prev_->next_ = next_;
    else impl_->processes = next_;
    if (next_ != nullptr) next_->prev_ = prev_;
    --impl_->live_processes;
  }
  ProcessPromise(const ProcessPromise&) = delete;
  ProcessPromise& operator=(const ProcessPromise&) = delete;

  Process get_return_object() noexcept {
    return {std::coroutine_handle<ProcessPromise>::from_promise(*this)};
  }
  std::suspend_always initial_suspend() const noexcept { return {}; }
  std::suspend_never final_suspend() const noexcept { return {}; }
  void return_void() const noexcept {}
  void unhandled_exception() noexcept {
    if (!impl_->failure) impl_->failure = std::current_exception();
  }
  ProcessPromise* next() const noexcept { return next_; }

 private:
  detail::SimulatorCore* impl_;
  ProcessPromise* prev_ = nullptr;
  ProcessPromise* next_ = nullptr;
};

Process run_process(detail::SimulatorCore& /*impl*/, Task<void> task) { co_await std::move(task); }

void resume_coroutine(void* address) { std::coroutine_handle<>::from_address(address).resume(); }

}  // namespace

Simulator::Simulator() : impl_(std::make_unique<detail::SimulatorCore>()) {}

Simulator::~Simulator() {
  // Destroy suspended processes first: their awaiters cancel the events they still own.
  while (impl_->processes != nullptr) {
    std::coroutine_handle<ProcessPromise>::from_promise(*impl_->processes).destroy();
  }
  impl_->queue.clear();
}

void Simulator::check_time(double time, const char* what) const {
  if (!(time >= now_) || std::isnan(time)) {
    throw SimulationError(
        fmt::format("{}: time {} s is before the current simulated time {} s", what, time, now_));
  }
}

void Simulator::spawn(Task<void> process) {
  if (!process.valid()) throw SimulationError("spawn: the task is empty (moved from?)");
  Process p = run_process(*impl_, std::move(process));
  wake(p.handle);
}

bool Simulator::step() {
  if (impl_->queue.empty()) return false;
  const auto fired = impl_->queue.pop();
  now_ = fired.time;
  ++events_processed_;
  fired.callback(fired.context);
  impl_->rethrow_failure();
  return true;
}

void Simulator::run() {
  while (step()) {
  }
}

void Simulator::run_until(double time) {
  check_time(time, "run_until");
  while (!impl_->queue.empty() && impl_->queue.top_time() <= time) step();
  now_ = time;
}

std::size_t Simulator::pending_events() const noexcept { return impl_->queue.size(); }
std::size_t Simulator::live_processes() const noexcept { return impl_->live_processes; }

SleepAwaiter Simulator::sleep(double delay) {
  if (!(delay >= 0.0)) throw SimulationError(fmt::format("sleep: negative delay {} s", delay));
  return SleepAwaiter(*this, now_ + delay);
}

SleepAwaiter Simulator::sleep_until(double time) {
  check_time(time, "sleep_until");
  return SleepAwaiter(*this, time);
}

EventHandle Simulator::schedule_at(double time, EventCallback callback, void* context) {
  check_time(time, "schedule_at");
  return EventHandle(impl_->queue.push(time, callback, context));
}

bool Simulator::cancel(EventHandle& event) noexcept {
  if (!event) return false;
  impl_->queue.erase(event.node_);
  event.reset();
  return true;
}

void Simulator::reschedule(const EventHandle& event, double time) {
  check_time(time, "reschedule");
  impl_->queue.update(event.node_, time);
}

double Simulator::due(const EventHandle& event) const noexcept { return event.node_->time; }

void Simulator::wake(std::coroutine_handle<> coroutine) {
  impl_->queue.push_now(now_, &resume_coroutine, coroutine.address());
}

SleepAwaiter::~SleepAwaiter() {
  if (event_) sim_->cancel(event_);
}

void SleepAwaiter::await_suspend(std::coroutine_handle<> waiting) {
  waiting_ = waiting;
  event_ = sim_->schedule_at(wake_time_, &SleepAwaiter::fire, this);
}

void SleepAwaiter::fire(void* self) {
  auto* awaiter = static_cast<SleepAwaiter*>(self);
  awaiter->event_.reset();
  awaiter->waiting_.resume();
}

}  // namespace pagecache
