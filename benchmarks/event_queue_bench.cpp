// Event queue: cost of scheduling and running one event with n events pending, and of
// cancelling one. Random delays go to the heap, O(log n) per event; equal delays (n processes
// in step, each waiting the same time) stay in one run of the queue, O(1) per event.
#include <pagecache/simulator.hpp>

#include <benchmark/benchmark.h>

#include <cstdint>
#include <random>
#include <vector>

namespace {

struct Reschedule {
  pagecache::Simulator* sim;
  std::mt19937_64* rng;
  std::int64_t* remaining;
};

// Each event schedules a successor at a random later time: the queue stays at n events.
void run_and_reschedule(void* context) {
  auto* ctx = static_cast<Reschedule*>(context);
  if (--*ctx->remaining <= 0) return;
  std::uniform_real_distribution<double> delay(0.0, 1.0);
  ctx->sim->schedule_at(ctx->sim->now() + delay(*ctx->rng), &run_and_reschedule, context);
}

void BM_EventQueueScheduleRun(benchmark::State& state) {
  const auto pending = state.range(0);
  std::mt19937_64 rng(42);
  std::int64_t processed = 0;
  for (auto _ : state) {
    state.PauseTiming();
    pagecache::Simulator sim;
    std::int64_t remaining = pending * 20;
    Reschedule ctx{&sim, &rng, &remaining};
    std::uniform_real_distribution<double> start(0.0, 1.0);
    for (std::int64_t i = 0; i < pending; ++i) sim.schedule_at(start(rng), &run_and_reschedule, &ctx);
    state.ResumeTiming();
    sim.run();
    processed += static_cast<std::int64_t>(sim.events_processed());
  }
  state.SetItemsProcessed(processed);
}
BENCHMARK(BM_EventQueueScheduleRun)->RangeMultiplier(10)->Range(10, 100000)->Unit(benchmark::kMillisecond);

struct Repeat {
  pagecache::Simulator* sim;
  std::int64_t* remaining;
};

// Each event schedules its successor one second later.
void run_and_repeat(void* context) {
  auto* ctx = static_cast<Repeat*>(context);
  if (--*ctx->remaining <= 0) return;
  ctx->sim->schedule_at(ctx->sim->now() + 1.0, &run_and_repeat, context);
}

void BM_EventQueueEqualDelays(benchmark::State& state) {
  const auto pending = state.range(0);
  std::int64_t processed = 0;
  for (auto _ : state) {
    state.PauseTiming();
    pagecache::Simulator sim;
    std::int64_t remaining = pending * 20;
    Repeat ctx{&sim, &remaining};
    for (std::int64_t i = 0; i < pending; ++i) sim.schedule_at(static_cast<double>(i) / static_cast<double>(pending), &run_and_repeat, &ctx);
    state.ResumeTiming();
    sim.run();
    processed += static_cast<std::int64_t>(sim.events_processed());
  }
  state.SetItemsProcessed(processed);
}
BENCHMARK(BM_EventQueueEqualDelays)->RangeMultiplier(10)->Range(10, 100000)->Unit(benchmark::kMillisecond);

void noop(void*) {}

void BM_EventQueueCancel(benchmark::State& state) {
  const auto pending = state.range(0);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> when(0.0, 1000.0);
  pagecache::Simulator sim;
  std::vector<pagecache::EventHandle> handles;
  for (std::int64_t i = 0; i < pending; ++i) handles.push_back(sim.schedule_at(when(rng), &noop, nullptr));
  std::size_t next = 0;
  for (auto _ : state) {
    // Cancel one event and schedule a replacement: the queue size stays at n.
    sim.cancel(handles[next]);
    handles[next] = sim.schedule_at(when(rng), &noop, nullptr);
    next = (next + 1) % handles.size();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
}
BENCHMARK(BM_EventQueueCancel)->RangeMultiplier(10)->Range(10, 100000);

}  // namespace
