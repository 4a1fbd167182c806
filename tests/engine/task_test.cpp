#include <pagecache/simulator.hpp>
#include <pagecache/task.hpp>

#include <catch2/catch.hpp>

#include <memory>
#include <stdexcept>
#include <string>

using pagecache::Simulator;
using pagecache::Task;

namespace {

Task<int> ready_value(int v) { co_return v; }

Task<void> sum_ready_tasks(int count, long& sum) {
  for (int i = 0; i < count; ++i) sum += co_await ready_value(i);
}

Task<int> throws_after_sleep(Simulator& sim) {
  co_await sim.sleep(1.0);
  throw std::runtime_error("boom");
}

Task<void> catches(Simulator& sim, std::string& seen) {
  try {
    (void)co_await throws_after_sleep(sim);
  } catch (const std::runtime_error& e) {
    seen = e.what();
  }
}

Task<std::unique_ptr<int>> move_only_value() { co_return std::make_unique<int>(42); }

Task<void> nested(Simulator& sim, int depth, int& reached) {
  if (depth == 0) {
    co_await sim.sleep(0.5);
    reached = 1;
    co_return;
  }
  co_await nested(sim, depth - 1, reached);
}

}  // namespace

TEST_CASE("awaiting 100000 ready tasks in a loop keeps the stack flat", "[task]") {
  Simulator sim;
  long sum = 0;
  sim.spawn(sum_ready_tasks(100000, sum));
  sim.run();
  CHECK(sum == 100000L * 99999L / 2);
}

TEST_CASE("a task's exception is rethrown at its co_await", "[task]") {
  Simulator sim;
  std::string seen;
  sim.spawn(catches(sim, seen));
  sim.run();
  CHECK(seen == "boom");
  CHECK(sim.now() == 1.0);
}

TEST_CASE("a task can return a move-only value", "[task]") {
  Simulator sim;
  int got = 0;
  auto consumer = [](int& out) -> Task<void> { out = *(co_await move_only_value()); };
  sim.spawn(consumer(got));
  sim.run();
  CHECK(got == 42);
}

TEST_CASE("a task suspended deep in a chain of awaits resumes its whole chain", "[task]") {
  Simulator sim;
  int reached = 0;
  sim.spawn(nested(sim, 1000, reached));
  sim.run();
  CHECK(reached == 1);
  CHECK(sim.now() == 0.5);
}

TEST_CASE("a task does nothing until awaited", "[task]") {
  bool ran = false;
  auto body = [](bool& flag) -> Task<void> {
    flag = true;
    co_return;
  };
  {
    Task<void> t = body(ran);
    CHECK(t.valid());
  }
  CHECK_FALSE(ran);
}
