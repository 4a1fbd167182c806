#include <pagecache/event.hpp>
#include <pagecache/simulator.hpp>

#include <catch2/catch.hpp>

#include <utility>
#include <vector>

using pagecache::Event;
using pagecache::Simulator;
using pagecache::Task;

namespace {

using Log = std::vector<std::pair<int, double>>;  // (waiter id, time resumed)

Task<void> wait_then_log(Simulator& sim, Event& event, int id, Log& log) {
  co_await event.wait();
  log.emplace_back(id, sim.now());
}

Task<void> trigger_at(Simulator& sim, Event& event, double when) {
  co_await sim.sleep(when);
  event.trigger();
}

Task<void> timed_wait(Simulator& sim, Event& event, double timeout, int& outcome, double& at) {
  outcome = co_await event.wait_for(timeout) ? 1 : 0;
  at = sim.now();
}

}  // namespace

TEST_CASE("an event wakes all its waiters at the trigger time, in waiting order", "[event]") {
  Simulator sim;
  Event event(sim);
  Log log;
  for (int id = 0; id < 5; ++id) sim.spawn(wait_then_log(sim, event, id, log));
  sim.spawn(trigger_at(sim, event, 3.0));
  sim.run_until(1.0);
  CHECK(event.waiting() == 5);
  sim.run();
  REQUIRE(log.size() == 5);
  for (int id = 0; id < 5; ++id) CHECK(log[static_cast<std::size_t>(id)] == std::make_pair(id, 3.0));
  CHECK(event.waiting() == 0);
}

TEST_CASE("waiting on an event already triggered completes at once", "[event]") {
  Simulator sim;
  Event event(sim);
  event.trigger();
  event.trigger();  // no further effect
  Log log;
  sim.run_until(2.0);
  sim.spawn(wait_then_log(sim, event, 9, log));
  sim.run();
  CHECK(log == Log{{9, 2.0}});
}

TEST_CASE("wait_for reports a trigger before the timeout", "[event]") {
  Simulator sim;
  Event event(sim);
  int outcome = -1;
  double at = -1.0;
  sim.spawn(timed_wait(sim, event, 10.0, outcome, at));
  sim.spawn(trigger_at(sim, event, 4.0));
  sim.run();
  CHECK(outcome == 1);
  CHECK(at == 4.0);
  // The timeout was cancelled: nothing else ran at t = 10.
  CHECK(sim.now() == 4.0);
}

TEST_CASE("wait_for reports a timeout and leaves the event's waiter list", "[event]") {
  Simulator sim;
  Event event(sim);
  int outcome = -1;
  double at = -1.0;
  sim.spawn(timed_wait(sim, event, 2.5, outcome, at));
  sim.run();
  CHECK(outcome == 0);
  CHECK(at == 2.5);
  CHECK(event.waiting() == 0);
  event.trigger();  // nobody left to wake
  sim.run();
  CHECK(sim.now() == 2.5);
}

TEST_CASE("a waiter on a destroyed event is never resumed", "[event]") {
  Simulator sim;
  Log log;
  {
    Event event(sim);
    sim.spawn(wait_then_log(sim, event, 1, log));
    sim.run();
    CHECK(event.waiting() == 1);
  }
  sim.run();
  CHECK(log.empty());
  CHECK(sim.live_processes() == 1);
}
