// Where and when workflow tasks run (CoreScheduler through run_scenario): a task's own host or
// the first of its workflow's hosts with room, several cores per task, waiting tasks served as
// they fit; what a task holds in memory; transfers over routes of several links and fatpipes.

#include <pagecache/error.hpp>
#include <pagecache/run.hpp>
#include <pagecache/scenario.hpp>
#include <pagecache/scenario_file.hpp>

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <map>
#include <string>
#include <utility>

namespace pagecache {
namespace {

// Hosts h1, h2, h3 (cores as given, 10 GB of memory, a 100 MB/s disk each), and `workflow`.
Scenario hosts_and(const std::string& workflow, int h1 = 1, int h2 = 1, int h3 = 1) {
  std::string text = "profile = \"paper\"\n";
  const int cores[] = {h1, h2, h3};
  for (int i = 0; i < 3; ++i) {
    text += fmt::format(R"(
[[hosts]]
name = "h{}"
cores = {}
memory = "10 GB"
memory_read_bw = "1 GB/s"
memory_write_bw = "1 GB/s"
[[hosts.disks]]
name = "d"
read_bw = "100 MB/s"
write_bw = "100 MB/s"
)",
                        i + 1, cores[i]);
  }
  return parse_scenario(text + workflow, "<placement test>");
}

// Each task's compute phase: (start, end), by task name.
std::map<std::string, std::pair<double, double>> computes(const RunResult& r) {
  std::map<std::string, std::pair<double, double>> out;
  for (const PhaseRow& row : r.timeline) {
    if (row.phase == PhaseKind::Compute) out[r.task_name(row)] = {row.start, row.end};
  }
  return out;
}

std::string task(const std::string& name, const std::string& extra = "") {
  return fmt::format("\n[[workflow.tasks]]\nname = \"{}\"\ncompute = \"10 s\"\n{}\n", name, extra);
}

}  // namespace

TEST_CASE("a task without a host goes to the first of its workflow's hosts with a free core, the others wait in order", "[run][placement]") {
  const std::string wf = "[workflow]\nhosts = [\"h2\", \"h1\"]\n" + task("a") + task("b") + task("c") + task("d") + task("e");
  const auto c = computes(run_scenario(hosts_and(wf)));
  CHECK(c.at("a") == std::pair{0.0, 10.0});
  CHECK(c.at("b") == std::pair{0.0, 10.0});
  CHECK(c.at("c") == std::pair{10.0, 20.0});
  CHECK(c.at("d") == std::pair{10.0, 20.0});
  CHECK(c.at("e") == std::pair{20.0, 30.0});
}

TEST_CASE("a task named to a host runs there, and needs its cores free there", "[run][placement]") {
  // h1 has 2 cores: x (2 cores) waits for a and b to give both back; c runs on h3 at once.
  const std::string wf = "[workflow]\nhosts = [\"h1\"]\n" + task("a") + task("b") + task("x", "cores = 2") + task("c", "host = \"h3\"");
  const auto c = computes(run_scenario(hosts_and(wf, 2)));
  CHECK(c.at("a").first == 0.0);
  CHECK(c.at("b").first == 0.0);
  CHECK(c.at("c").first == 0.0);
  CHECK(c.at("x") == std::pair{10.0, 20.0});
}

TEST_CASE("a waiting task that needs many cores does not hold back a later one that fits", "[run][placement]") {
  // h1 has 3 cores: a (2 cores) and b (1) run; x (3) must wait for all three; y (1), ready
  // after x, takes the core b gives back at 5 s while x still waits for a's two.
  const std::string wf = "[workflow]\nhosts = [\"h1\"]\n" + task("a", "cores = 2") +
                         "\n[[workflow.tasks]]\nname = \"b\"\ncompute = \"5 s\"\n" + task("x", "cores = 3") + task("y");
  const auto c = computes(run_scenario(hosts_and(wf, 3)));
  CHECK(c.at("a") == std::pair{0.0, 10.0});
  CHECK(c.at("b") == std::pair{0.0, 5.0});
  CHECK(c.at("y") == std::pair{5.0, 15.0});
  CHECK(c.at("x") == std::pair{15.0, 25.0});
}

TEST_CASE("a task needing more cores than any host it may run on has is refused before the run", "[run][placement][errors]") {
  const std::string wf = "[workflow]\nhosts = [\"h1\", \"h2\"]\n" + task("big", "cores = 3");
  CHECK_THROWS_WITH(run_scenario(hosts_and(wf, 2, 2)), Catch::Contains("task 'big': needs 3 cores"));
}

TEST_CASE("a task's memory is taken from the cache: clean data is evicted to make room for it", "[run][memory]") {
  // 10 GB of memory, an 8 GB input cached at the start; the task holds 6 GB and reads a 1 GB
  // file (1 GB cached, and 1 GB in its buffer, counted within its 6 GB): 8 + 1 + 6 = 15 GB,
  // 5 GB more than the memory: 5 GB of the clean cache go. Without its memory it would fit.
  const std::string wf = R"(
[[files]]
name = "big"
size = "8 GB"
host = "h1"
cached = true
[[files]]
name = "small"
size = "1 GB"
host = "h1"
[workflow]
host = "h1"
[[workflow.tasks]]
name = "t"
memory = "6 GB"
read = "small"
)";
  const RunResult r = run_scenario(hosts_and(wf));
  REQUIRE(r.files == std::vector<std::string>{"big", "small"});
  const CacheRow& big_after_read = r.cache.at(0);
  CHECK(big_after_read.cached == 3'000'000'000);
  CHECK(r.summary.evicted_bytes == 5'000'000'000);
  // Without the memory, nothing is evicted.
  Scenario light = hosts_and(wf);
  light.workflows.front().tasks.front().memory = 0;
  CHECK(run_scenario(light).summary.evicted_bytes == 0);
}

TEST_CASE("a task whose memory no eviction can free fails with the simulated time", "[run][memory][errors]") {
  const std::string wf = "[workflow]\nhost = \"h1\"\n" + task("t", "memory = \"11 GB\"");
  CHECK_THROWS_AS(run_scenario(hosts_and(wf)), SimulationError);
  CHECK_THROWS_WITH(run_scenario(hosts_and(wf)), Catch::Contains("t = 0.000000 s") && Catch::Contains("the task's memory needs"));
}

TEST_CASE("a file on another host is read over its route: the slowest link sets the pace, the latencies add up", "[run][routes]") {
  // h1 reads 1 GB from h2's disk (100 MB/s) over links of 1 GB/s, 50 MB/s and 500 MB/s: 20 s
  // at 50 MB/s, after 1 + 2 + 3 ms of latency per chunk of 100 MB (ten chunks).
  const std::string wf = R"(
[[links]]
name = "a"
bandwidth = "1 GB/s"
latency = "1 ms"
[[links]]
name = "b"
bandwidth = "50 MB/s"
latency = "2 ms"
[[links]]
name = "c"
bandwidth = "500 MB/s"
latency = "3 ms"
[[routes]]
hosts = ["h1", "h2"]
links = ["a", "b", "c"]
[[files]]
name = "remote"
size = "1 GB"
host = "h2"
[workflow]
host = "h1"
[[workflow.tasks]]
name = "t"
read = "remote"
)";
  const RunResult r = run_scenario(hosts_and(wf));
  const PhaseRow& read = r.timeline.front();
  CHECK(read.end - read.start == Approx(20.0 + 10 * 0.006).epsilon(1e-9));
}

TEST_CASE("a fatpipe link bounds each flow without sharing its bandwidth", "[run][routes]") {
  // Two tasks on h1 read one file each from h2 over a 60 MB/s link, at once. Shared, the
  // link gives each 30 MB/s (1 GB: 33.3 s), the disk (100 MB/s) could give 50; as a fatpipe,
  // each gets 50 MB/s, the disk's share (20 s).
  std::string wf = R"(
[[links]]
name = "l"
bandwidth = "60 MB/s"
SHARING
hosts = ["h1", "h2"]
[[files]]
name = "f1"
size = "1 GB"
host = "h2"
[[files]]
name = "f2"
size = "1 GB"
host = "h2"
[workflow]
hosts = ["h1"]
[[workflow.tasks]]
name = "t1"
read = "f1"
[[workflow.tasks]]
name = "t2"
read = "f2"
)";
  const auto read_time = [&](const char* sharing) {
    std::string text = wf;
    text.replace(text.find("SHARING"), 7, sharing);
    const RunResult r = run_scenario(hosts_and(text, 2));
    return r.timeline.front().end - r.timeline.front().start;
  };
  CHECK(read_time("sharing = \"shared\"") == Approx(1e9 / 30e6).epsilon(1e-6));
  CHECK(read_time("sharing = \"fatpipe\"") == Approx(20.0).epsilon(1e-6));
}

}  // namespace pagecache

namespace pagecache {

TEST_CASE("a route in a scenario names known hosts and links, and two hosts have one link or route", "[scenario][routes][errors]") {
  const std::string links = R"(
[[links]]
name = "a"
bandwidth = "1 GB/s"
[[links]]
name = "b"
bandwidth = "1 GB/s"
hosts = ["h1", "h3"]
[workflow]
host = "h1"
[[workflow.tasks]]
name = "t"
)";
  const auto error = [&](const std::string& route) {
    try {
      hosts_and(links + route);
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  CHECK_THAT(error("[[routes]]\nhosts = [\"h1\", \"h2\"]\nlinks = [\"c\"]\n"), Catch::Contains("key 'routes[0].links': no link named 'c'"));
  CHECK_THAT(error("[[routes]]\nhosts = [\"h1\", \"h9\"]\nlinks = [\"a\"]\n"), Catch::Contains("key 'routes[0].hosts': no host named 'h9'"));
  CHECK_THAT(error("[[routes]]\nhosts = [\"h3\", \"h1\"]\nlinks = [\"a\"]\n"), Catch::Contains("these hosts already have a link or a route"));
  CHECK_THAT(error("[[routes]]\nhosts = [\"h1\", \"h2\"]\nlinks = []\n"), Catch::Contains("a route crosses at least one link"));
  CHECK(error("[[routes]]\nhosts = [\"h1\", \"h2\"]\nlinks = [\"a\", \"b\"]\n") == "(no error)");
}

}  // namespace pagecache
