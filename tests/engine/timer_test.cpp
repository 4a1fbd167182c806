#include <pagecache/error.hpp>
#include <pagecache/simulator.hpp>
#include <pagecache/timer.hpp>

#include <catch2/catch.hpp>

#include <vector>

using pagecache::Simulator;
using pagecache::Timer;

TEST_CASE("a timer fires once at its due time", "[timer]") {
  Simulator sim;
  std::vector<double> fired;
  Timer timer(sim, [&] { fired.push_back(sim.now()); });
  timer.arm_in(2.0);
  CHECK(timer.armed());
  CHECK(timer.due() == 2.0);
  sim.run();
  CHECK(fired == std::vector<double>{2.0});
  CHECK_FALSE(timer.armed());
}

TEST_CASE("a cancelled timer never fires, and cancelling twice is harmless", "[timer]") {
  Simulator sim;
  int fired = 0;
  Timer timer(sim, [&] { ++fired; });
  timer.arm_at(5.0);
  CHECK(timer.cancel());
  CHECK_FALSE(timer.cancel());
  sim.run();
  CHECK(fired == 0);
  CHECK(sim.events_processed() == 0);
}

TEST_CASE("re-arming a timer moves it instead of adding a second firing", "[timer]") {
  Simulator sim;
  std::vector<double> fired;
  Timer timer(sim, [&] { fired.push_back(sim.now()); });
  timer.arm_at(5.0);
  timer.arm_at(1.0);
  sim.run();
  CHECK(fired == std::vector<double>{1.0});
}

TEST_CASE("a timer can re-arm itself from its callback to run periodically", "[timer]") {
  Simulator sim;
  std::vector<double> fired;
  Timer* self = nullptr;
  Timer timer(sim, [&] {
    fired.push_back(sim.now());
    if (fired.size() < 3) self->arm_in(5.0);
  });
  self = &timer;
  timer.arm_in(5.0);
  sim.run();
  CHECK(fired == std::vector<double>{5.0, 10.0, 15.0});
}

TEST_CASE("a timer destroyed while armed does not fire", "[timer]") {
  Simulator sim;
  int fired = 0;
  {
    Timer timer(sim, [&] { ++fired; });
    timer.arm_in(1.0);
  }
  sim.run();
  CHECK(fired == 0);
}

TEST_CASE("a timer cannot be armed in the past", "[timer]") {
  Simulator sim;
  Timer timer(sim, [] {});
  sim.run_until(3.0);
  CHECK_THROWS_AS(timer.arm_at(2.0), pagecache::SimulationError);
  CHECK_THROWS_AS(timer.arm_in(-1.0), pagecache::SimulationError);
}
