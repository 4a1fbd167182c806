#include <pagecache/timer.hpp>

#include <pagecache/error.hpp>

#include <fmt/format.h>

namespace pagecache {

Timer::Timer(Simulator& sim, std::function<void()> on_fire) : sim_(&sim), on_fire_(std::move(on_fire)) {}

Timer::~Timer() { cancel(); }

void Timer::arm_at(double time) {
  if (event_) sim_->reschedule(event_, time);
  else event_ = sim_->schedule_at(time, &Timer::fire, this);
}

void Timer::arm_in(double delay) {
  if (!(delay >= 0.0)) throw SimulationError(fmt::format("Timer::arm_in: negative delay {} s", delay));
  arm_at(sim_->now() + delay);
}

bool Timer::cancel() noexcept { return sim_->cancel(event_); }

double Timer::due() const noexcept { return sim_->due(event_); }

void Timer::fire(void* self) {
  auto* timer = static_cast<Timer*>(self);
  timer->event_.reset();
  timer->on_fire_();
}

}  // namespace pagecache
