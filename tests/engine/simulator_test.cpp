#include <pagecache/error.hpp>
#include <pagecache/simulator.hpp>

#include <catch2/catch.hpp>

#include <stdexcept>
#include <string>
#include <vector>

using pagecache::Simulator;
using pagecache::Task;

namespace {

Task<void> record_after(Simulator& sim, double delay, int id, std::vector<int>& order) {
  co_await sim.sleep(delay);
  order.push_back(id);
}

Task<void> fail_at(Simulator& sim, double when) {
  co_await sim.sleep(when);
  throw std::logic_error("process failed");
}

Task<void> sleep_forever_on(Simulator& sim, int& destroyed_marker) {
  struct Marker {
    int* target;
    ~Marker() { ++*target; }
  } marker{&destroyed_marker};
  co_await sim.sleep(1e9);
}

void record(void* context) { static_cast<std::vector<double>*>(context)->push_back(0.0); }

}  // namespace

TEST_CASE("events at equal times run in the order they were scheduled", "[simulator]") {
  Simulator sim;
  std::vector<int> order;
  for (int id = 0; id < 50; ++id) sim.spawn(record_after(sim, 2.0, id, order));
  sim.run();
  REQUIRE(order.size() == 50);
  for (int id = 0; id < 50; ++id) CHECK(order[static_cast<std::size_t>(id)] == id);
  CHECK(sim.now() == 2.0);
}

TEST_CASE("sleep(0) yields to the events already due now", "[simulator]") {
  Simulator sim;
  std::vector<int> order;
  sim.spawn(record_after(sim, 0.0, 1, order));
  sim.spawn(record_after(sim, 0.0, 2, order));
  sim.run();
  CHECK(order == std::vector<int>{1, 2});
  CHECK(sim.now() == 0.0);
}

TEST_CASE("events run in time order whatever their scheduling order", "[simulator]") {
  Simulator sim;
  std::vector<int> order;
  sim.spawn(record_after(sim, 3.0, 3, order));
  sim.spawn(record_after(sim, 1.0, 1, order));
  sim.spawn(record_after(sim, 2.0, 2, order));
  sim.run();
  CHECK(order == std::vector<int>{1, 2, 3});
}

TEST_CASE("an exception escaping a process stops run() and is rethrown from it", "[simulator]") {
  Simulator sim;
  std::vector<int> order;
  sim.spawn(fail_at(sim, 1.0));
  sim.spawn(record_after(sim, 2.0, 7, order));
  REQUIRE_THROWS_WITH(sim.run(), "process failed");
  CHECK(sim.now() == 1.0);
  CHECK(order.empty());
  // The other process is still there and the simulator can go on.
  sim.run();
  CHECK(order == std::vector<int>{7});
}

TEST_CASE("two simulators in one process do not interfere", "[simulator]") {
  Simulator a;
  Simulator b;
  std::vector<int> order_a;
  std::vector<int> order_b;
  a.spawn(record_after(a, 5.0, 1, order_a));
  b.spawn(record_after(b, 1.0, 2, order_b));
  b.run();
  CHECK(b.now() == 1.0);
  CHECK(a.now() == 0.0);
  CHECK(order_a.empty());
  a.run();
  CHECK(a.now() == 5.0);
  CHECK(order_a == std::vector<int>{1});
  CHECK(order_b == std::vector<int>{2});
}

TEST_CASE("run_until stops at the given time and leaves later events pending", "[simulator]") {
  Simulator sim;
  std::vector<int> order;
  sim.spawn(record_after(sim, 1.0, 1, order));
  sim.spawn(record_after(sim, 3.0, 3, order));
  sim.run_until(2.0);
  CHECK(order == std::vector<int>{1});
  CHECK(sim.now() == 2.0);
  CHECK(sim.live_processes() == 1);
  sim.run();
  CHECK(order == std::vector<int>{1, 3});
  CHECK(sim.live_processes() == 0);
}

TEST_CASE("destroying a simulator destroys its suspended processes", "[simulator]") {
  int destroyed = 0;
  {
    Simulator sim;
    sim.spawn(sleep_forever_on(sim, destroyed));
    sim.run_until(1.0);
    CHECK(sim.live_processes() == 1);
    CHECK(destroyed == 0);
  }
  CHECK(destroyed == 1);
}

TEST_CASE("scheduling in the past or sleeping a negative time is an error", "[simulator]") {
  Simulator sim;
  sim.run_until(5.0);
  std::vector<double> calls;
  CHECK_THROWS_AS(sim.schedule_at(4.0, &record, &calls), pagecache::SimulationError);
  CHECK_THROWS_AS(sim.sleep(-1.0), pagecache::SimulationError);
  CHECK_THROWS_AS(sim.run_until(1.0), pagecache::SimulationError);
}

TEST_CASE("a cancelled event never runs and a rescheduled one runs at its new time", "[simulator]") {
  Simulator sim;
  std::vector<double> calls;
  auto cancelled = sim.schedule_at(1.0, &record, &calls);
  auto moved = sim.schedule_at(1.0, &record, &calls);
  CHECK(sim.pending_events() == 2);
  CHECK(sim.cancel(cancelled));
  CHECK_FALSE(cancelled);
  CHECK_FALSE(sim.cancel(cancelled));
  sim.reschedule(moved, 4.0);
  CHECK(sim.due(moved) == 4.0);
  sim.run();
  CHECK(calls.size() == 1);
  CHECK(sim.now() == 4.0);
  CHECK(sim.events_processed() == 1);
}

TEST_CASE("a rescheduled event goes after the events already scheduled for its new time", "[simulator]") {
  Simulator sim;
  std::vector<int> order;
  struct Ctx {
    std::vector<int>* order;
    int id;
  };
  Ctx first{&order, 1};
  Ctx second{&order, 2};
  auto push = [](void* c) {
    auto* ctx = static_cast<Ctx*>(c);
    ctx->order->push_back(ctx->id);
  };
  auto e1 = sim.schedule_at(0.5, push, &first);
  sim.schedule_at(2.0, push, &second);
  sim.reschedule(e1, 2.0);
  sim.run();
  CHECK(order == std::vector<int>{2, 1});
}
