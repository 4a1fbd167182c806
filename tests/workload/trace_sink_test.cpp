// The trace sink: what the runner, the fair-share model and the page cache report agrees with
// the run's own tallies (RunResult and its summary), whichever profile made it.

#include <pagecache/run.hpp>
#include <pagecache/scenario.hpp>
#include <pagecache/scenario_file.hpp>
#include <pagecache/trace.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <map>
#include <string>
#include <vector>

namespace pagecache {
namespace {

// Tallies everything it is told.
struct Tally final : TraceSink {
  int starts = 0, ends = 0;
  std::vector<std::string> hosts;
  std::vector<PhaseEvent> phases;  // names not kept: they live as long as the run
  std::map<std::string, double> work_per_resource;
  std::map<FlushCause, std::int64_t> flushed;
  std::int64_t evicted = 0;
  double throttled_seconds = 0.0;
  std::size_t memory_rows = 0, cache_events = 0;
  double last_time = 0.0;
  bool in_order = true;  // events come at non-decreasing times

  void at(double t) {
    in_order = in_order && t >= last_time;
    last_time = t;
  }
  void on_start(const TraceStart& s) override {
    ++starts;
    hosts.assign(s.hosts.begin(), s.hosts.end());
  }
  void on_phase(const PhaseEvent& e) override {
    at(e.end);
    phases.push_back(e);
    phases.back().app = phases.back().task = {};
  }
  void on_flow(const FlowEvent& e) override {
    at(e.end);
    for (const std::string_view r : e.resources) work_per_resource[std::string(r)] += e.work;
  }
  void on_flush(const FlushEvent& e) override {
    at(e.time);
    flushed[e.cause] += e.bytes;
  }
  void on_eviction(const EvictionEvent& e) override {
    at(e.time);
    evicted += e.bytes;
  }
  void on_throttle(const ThrottleEvent& e) override {
    at(e.end);
    CHECK(e.start <= e.end);
    throttled_seconds += e.end - e.start;
  }
  void on_memory(const MemoryEvent& e) override {
    at(e.time);
    ++memory_rows;
  }
  void on_cache_contents(const CacheContentsEvent&) override { ++cache_events; }
  void on_end(double t) override {
    at(t);
    ++ends;
  }
};

Scenario exp2(const std::string& profile, int pipelines) {
  return load_scenario(std::string(PCSIM_SOURCE_DIR) + "/scenarios/paper/exp2.toml", {{"pipelines.count", std::to_string(pipelines)}}, profile);
}

// 16 writers against the dirty limit of a 64 GB machine.
Scenario many_writers(const std::string& profile) {
  return load_scenario(std::string(PCSIM_SOURCE_DIR) + "/scenarios/examples/many-writers.toml", {}, profile);
}

void check_agrees(const Scenario& scenario, const RunResult& r, const Tally& t) {
  CHECK(t.starts == 1);
  CHECK(t.ends == 1);
  CHECK(t.in_order);
  CHECK(t.hosts.size() == scenario.hosts.size());
  REQUIRE(t.phases.size() == r.timeline.size());
  for (std::size_t i = 0; i < r.timeline.size(); ++i) {
    CHECK(t.phases[i].row == i);
    CHECK(t.phases[i].kind == r.timeline[i].phase);
    CHECK(t.phases[i].start == r.timeline[i].start);
    CHECK(t.phases[i].end == r.timeline[i].end);
    CHECK(t.phases[i].bytes == r.timeline[i].bytes);
  }
  CHECK(t.memory_rows == r.memory.size());
  CHECK(t.cache_events * r.files.size() == r.cache.size());
  std::int64_t forced = 0, periodic = 0;
  for (const auto& [cause, bytes] : t.flushed) {
    (cause == FlushCause::Background || cause == FlushCause::Expiry ? periodic : forced) += bytes;
  }
  CHECK(forced == r.summary.forced_flush_bytes);
  CHECK(periodic == r.summary.periodic_flush_bytes);
  CHECK(t.evicted == r.summary.evicted_bytes);
}

TEST_CASE("the trace sink reports what the run tallies: paper profile", "[trace]") {
  const Scenario scenario = GENERATE(as<std::string>{}, "exp2", "many_writers") == "exp2" ? exp2("paper", 4) : many_writers("paper");
  Tally tally;
  RunOptions options;
  options.consumers = {&tally};
  const RunResult r = run_scenario(scenario, options);
  check_agrees(scenario, r, tally);
  // Every byte read from the disk went through it, and every byte written back.
  const std::string disk = scenario.hosts.front().name + ":" + scenario.hosts.front().disks.front().name;
  CHECK(tally.work_per_resource.at(disk) ==
        Approx(static_cast<double>(r.summary.disk_read_bytes + r.summary.forced_flush_bytes + r.summary.periodic_flush_bytes)));
  if (scenario.title.find("writers") != std::string::npos) CHECK(tally.flushed.count(FlushCause::DirtyLimit) == 1);
}

TEST_CASE("the trace sink reports what the run tallies: linux profile, throttled writers", "[trace]") {
  const Scenario scenario = many_writers("linux");
  Tally tally;
  RunOptions options;
  options.consumers = {&tally};
  const RunResult r = run_scenario(scenario, options);
  check_agrees(scenario, r, tally);
  CHECK(tally.flushed[FlushCause::Background] > 0);
  CHECK(tally.throttled_seconds > 0.0);
}

TEST_CASE("two consumers see the same run, and the run is the same without them", "[trace]") {
  const Scenario scenario = exp2("linux", 2);
  Tally a, b;
  RunOptions options;
  options.consumers = {&a, &b};
  const RunResult traced = run_scenario(scenario, options);
  const RunResult plain = run_scenario(scenario);
  CHECK(a.phases.size() == b.phases.size());
  CHECK(a.work_per_resource == b.work_per_resource);
  CHECK(a.flushed == b.flushed);
  REQUIRE(traced.timeline.size() == plain.timeline.size());
  for (std::size_t i = 0; i < plain.timeline.size(); ++i) CHECK(traced.timeline[i].end == plain.timeline[i].end);
  CHECK(traced.summary.events == plain.summary.events);
}

}  // namespace
}  // namespace pagecache
