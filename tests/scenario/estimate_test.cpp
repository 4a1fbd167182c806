// The estimate the limits check holds against ScenarioLimits before a run (src/scenario/
// estimate/estimate.hpp), against what the run then does: its events within a factor of 3 of the
// run's on every shipped scenario under both profiles and on shapes that each stress a source
// of events; and what it refuses, naming the key.

#include "estimate/estimate.hpp"

#include <pagecache/error.hpp>
#include <pagecache/run.hpp>
#include <pagecache/scenario_file.hpp>

#include "support/unchecked_runs.hpp"

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace pagecache {
namespace {

namespace fs = std::filesystem;
using Overrides = std::vector<std::pair<std::string, std::string>>;

const fs::path kSource = PCSIM_SOURCE_DIR;

// The runs here are counted, not checked: the page cache's invariants are other tests'
// business, and at these sizes (a cluster's 32,000 applications) would take hours.
using test::UncheckedRuns;

// The run's events over the estimate's, checked to be within a factor of 3 either way, with
// the estimate's sources for the message. False if the run failed (a scenario may be meant
// to: file-no-longer-fits.toml under the paper profile).
bool check_estimate(const std::string& name, const Scenario& s) {
  const estimate::RunEstimate e = estimate::estimate_run(s);
  RunOptions options;
  options.cache_contents = false;
  const UncheckedRuns unchecked;
  double actual = 0.0;
  try {
    actual = static_cast<double>(run_scenario(s, options).summary.events);
  } catch (const SimulationError& failed) {
    WARN(name << ": not compared, the run fails: " << failed.what());
    return false;
  }
  INFO(fmt::format("{}: estimated {:.4g} events (transfers {:.3g}, throttled writers' pauses {:.3g}, flushers' wake-ups {:.3g}, "
                   "memory sampler {:.3g}), the run took {:.4g}: {:.3f} times",
                   name, e.events(), e.transfer_events, e.throttle_events, e.flusher_events, e.sampler_events, actual,
                   e.events() / actual));
  CHECK(e.events() >= actual / 3.0);
  CHECK(e.events() <= actual * 3.0);
  return true;
}

// Every scenario file shipped: scenarios/ (its sweep files aside: each is many runs of a
// scenario there) and the golden scenarios.
std::vector<fs::path> shipped_scenarios() {
  std::vector<fs::path> out;
  for (const auto& entry : fs::recursive_directory_iterator(kSource / "scenarios")) {
    if (entry.path().extension() == ".toml" && entry.path().parent_path().filename() != "sweeps") out.push_back(entry.path());
  }
  for (const auto& entry : fs::directory_iterator(kSource / "tests/apps/golden")) {
    if (entry.path().extension() == ".toml") out.push_back(entry.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

TEST_CASE("the estimated events are within a factor of 3 of the run's, for every shipped scenario under both profiles", "[scenario][estimate]") {
  const std::vector<fs::path> files = shipped_scenarios();
  REQUIRE(files.size() >= 10);
  std::size_t compared = 0;
  for (const fs::path& file : files) {
    for (const char* profile : {"paper", "linux"}) {
      // Loaded with the default limits: a shipped scenario is never refused.
      const Scenario s = load_scenario(file.string(), {}, profile);
      compared += check_estimate(fmt::format("{} ({})", fs::relative(file, kSource).string(), profile), s) ? 1 : 0;
    }
  }
  // The paper's model never evicts the file being read whole: file-no-longer-fits.toml cannot
  // run under it.
  CHECK(compared >= 2 * files.size() - 1);
}

// One host of 40,000 cores running `count` pipelines of two tasks on 1 GB files at once (the
// shape of issue 33), with the memory their buffers need: the writers outrun the disk and
// dirty throttling pauses each of them a second at a time.
std::string many_writers(int count) {
  return fmt::format(R"(
profile = "linux"
[[hosts]]
name = "node"
cores = 40000
memory = "{} GB"
memory_in_use = "1.7 GB"
memory_read_bw = "6860 MB/s"
memory_write_bw = "2764 MB/s"
memory_aggregate_read_bw = "100 GB/s"
memory_aggregate_write_bw = "50 GB/s"
memory_first_touch_bw = "6.1 GB/s"
[[hosts.disks]]
name = "ssd"
read_bw = "510 MB/s"
write_bw = "516 MB/s"
[pipelines]
count = {}
file_size = "1 GB"
tasks = 2
cpu_time = "4.4 s"
)",
                     count * 3 / 2, count);
}

// A workflow of `count` tasks on a host of 400 cores, each reading its own input and writing
// its own output, a fifth of them fsync'ed and a seventh with direct I/O.
std::string wide_workflow(int count) {
  std::string text = R"(
profile = "linux"
[[hosts]]
name = "h"
cores = 400
memory = "800 GB"
memory_read_bw = "5 GB/s"
memory_write_bw = "3 GB/s"
memory_aggregate_read_bw = "50 GB/s"
memory_aggregate_write_bw = "30 GB/s"
[[hosts.disks]]
name = "d"
read_bw = "500 MB/s"
write_bw = "500 MB/s"
)";
  for (int i = 0; i < count; ++i) text += fmt::format("[[files]]\nname = \"in{0}\"\nsize = \"500 MB\"\n[[files]]\nname = \"out{0}\"\nsize = \"1 GB\"\n", i);
  text += "[workflow]\nname = \"wf\"\n";
  for (int i = 0; i < count; ++i) {
    text += fmt::format("[[workflow.tasks]]\nname = \"t{0}\"\nread = \"in{0}\"\ncompute = \"2 s\"\nwrite = \"out{0}\"\nfsync = {1}\ndirect_io = {2}\n", i,
                        i % 5 == 0, i % 7 == 0);
  }
  return text;
}

// 16 pipelines on a host whose memory their files do not fit: reads make room by evicting, and
// under the paper's model by writing dirty data back first.
constexpr const char* kTightMemory = R"(
memory_sample_interval = "1 s"
[[hosts]]
name = "h"
cores = 16
memory = "12 GB"
memory_read_bw = "5 GB/s"
memory_write_bw = "5 GB/s"
[[hosts.disks]]
name = "d"
read_bw = "500 MB/s"
write_bw = "400 MB/s"
[pipelines]
count = 16
file_size = "500 MB"
tasks = 4
cpu_time = "1 s"
chunk_size = "50 MB"
)";

// Pipelines reading and writing their files on a host far away: every chunk waits 50 ms.
constexpr const char* kFarFiles = R"(
platform = "../../platforms/paper-cluster.toml"
[[hosts]]
name = "far"
memory = "64 GB"
memory_read_bw = "5 GB/s"
memory_write_bw = "5 GB/s"
[[hosts.disks]]
name = "d"
read_bw = "500 MB/s"
write_bw = "400 MB/s"
[[links]]
name = "slow"
bandwidth = "1 GB/s"
latency = "50 ms"
hosts = ["node", "far"]
[pipelines]
count = 8
host = "node"
files_host = "far"
file_size = "2 GB"
tasks = 3
cpu_time = "2 s"
chunk_size = "20 MB"
)";

TEST_CASE("the estimated events are within a factor of 3 of the run's, for shapes that stress each source of events", "[scenario][estimate]") {
  const std::string examples = (kSource / "scenarios/examples").string();
  const std::string paper = (kSource / "scenarios/paper").string();
  // Scenario files are read relative to their folder: a shape written here is given a name in
  // the examples' folder, where it finds the platforms as they do.
  const std::string here = examples + "/shape.toml";
  for (const char* profile : {"paper", "linux"}) {
    INFO("profile " << profile);
    // Throttled writers' pauses: 600 writers at once against one disk.
    check_estimate("600 pipelines writing on one host", parse_scenario(many_writers(600), here, {}, profile));
    // A host group reading from and writing to one NFS server, as nfs-cluster.toml on 40 nodes;
    // then its server caching what it is written (writeback), whose writers are all the nodes'.
    check_estimate("40 nodes x 32 applications over NFS",
                   load_scenario(examples + "/nfs-cluster.toml", {{"hosts.0.count", "40"}, {"pipelines.count", "1280"}}, profile));
    check_estimate("20 nodes x 32 applications writing to an NFS server's writeback cache",
                   load_scenario(examples + "/nfs-cluster.toml",
                                 {{"hosts.0.count", "20"}, {"pipelines.count", "640"}, {"hosts.1.page_cache.mode", "\"writeback\""}}, profile));
    // Route latency: a wait per chunk.
    check_estimate("pipelines over a 50 ms link", parse_scenario(kFarFiles, here, {}, profile));
    // A workflow's tasks writing at once, as many as the cores hold; fsync and direct I/O.
    check_estimate("a workflow of 400 tasks", parse_scenario(wide_workflow(400), here, {}, profile));
    // Reclaim: reads making room, by writebacks under the paper's model.
    check_estimate("16 pipelines in too little memory", parse_scenario(kTightMemory, here, {}, profile));
    // Memory groups: each pipeline's writer throttled against its group's own limits.
    check_estimate("8 pipelines in memory groups", load_scenario(examples + "/memory-limit.toml", {{"pipelines.count", "8"}}, profile));
    // The memory sampler at every change, and the flusher ticking every 10 ms.
    check_estimate("exp2 sampled every millisecond", load_scenario(paper + "/exp2.toml", {{"memory_sample_interval", "\"1 ms\""}}, profile));
    check_estimate("exp1 with a flusher waking every 10 ms",
                   load_scenario(paper + "/exp1.toml", {{"hosts.0.page_cache.writeback_interval", "\"10 ms\""}}, profile));
  }
}

TEST_CASE("many writers on one host are refused before they run when their pauses alone exceed the events a run may take", "[scenario][estimate]") {
  // Issue 33: 40,000 pipelines of two tasks on 1 GB files were estimated at 5 * 10^6 events
  // (three per chunk operation) and ran for hours. Their writers pause about 6 * 10^9 times.
  const std::string text = many_writers(40'000);
  try {
    parse_scenario(text, "many.toml");
    FAIL("loaded");
  } catch (const ConfigError& e) {
    CHECK_THAT(e.what(), Catch::StartsWith("many.toml:3:1: key 'hosts[0].page_cache.dirty_throttling'") &&
                             Catch::Contains("the writers of host 'node' would pause about") && Catch::Contains("without --force"));
  }
  const estimate::RunEstimate e = estimate::estimate_run(parse_scenario(text, "many.toml", {}, {}, ScenarioLimits::forced()));
  CHECK(e.throttle_events > ScenarioLimits{}.max_events);
  CHECK(e.transfer_events < ScenarioLimits{}.max_events / 100.0);
}

// Two hosts joined by `links`, which a pipeline reading `chunks` chunks of 100 MB over them crosses.
std::string remote_reader(const std::string& links, int chunks) {
  return fmt::format(R"(
[[hosts]]
name = "node"
memory = "8 GB"
memory_read_bw = "5 GB/s"
memory_write_bw = "5 GB/s"
[[hosts.disks]]
name = "d"
read_bw = "500 MB/s"
write_bw = "500 MB/s"
[[hosts]]
name = "storage"
memory = "8 GB"
memory_read_bw = "5 GB/s"
memory_write_bw = "5 GB/s"
[[hosts.disks]]
name = "d"
read_bw = "500 MB/s"
write_bw = "500 MB/s"
{}
[[files]]
name = "far"
size = "{} MB"
host = "storage"
[[apps]]
name = "reader"
host = "node"
[[apps.tasks]]
read = "far"
)",
                     links, 100 * chunks);
}

std::string error_of(const std::string& text, const ScenarioLimits& limits) {
  try {
    parse_scenario(text, "s.toml", {}, {}, limits);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(loaded)";
}

TEST_CASE("a link's latency, paid by every transfer over it, is refused at load naming its key when the run would outlast the limit", "[scenario][estimate]") {
  const std::string link = "[[links]]\nname = \"net\"\nbandwidth = \"1 GB/s\"\nlatency = \"{}\"\nhosts = [\"node\", \"storage\"]\n";
  // Just under the longest duration pcsim takes, twenty times over: 2 * 10^10 s, past what the
  // run itself allows (RunOptions::max_simulated_time), whatever --force says.
  const std::string slow = remote_reader(fmt::format(fmt::runtime(link), "999999999 s"), 20);
  for (const ScenarioLimits& limits : {ScenarioLimits{}, ScenarioLimits::forced()}) {
    CHECK_THAT(error_of(slow, limits), Catch::StartsWith("s.toml:23:11: key 'links[0].latency': the run would take at least about 2e+10 s") &&
                                           Catch::Contains("application 'reader' waiting 2e+10 s for the latency of its routes"));
  }
  // 10^7 s twenty times: more than a run may take without --force, and it runs with it.
  const std::string long_one = remote_reader(fmt::format(fmt::runtime(link), "1e7 s"), 20);
  CHECK_THAT(error_of(long_one, {}), Catch::StartsWith("s.toml:23:11: key 'links[0].latency'") && Catch::Contains("without --force"));
  CHECK(run_scenario(parse_scenario(long_one, "s.toml", {}, {}, ScenarioLimits::forced())).summary.makespan >= 1e8);
}

TEST_CASE("the latencies along a route add up, each transfer paying them all", "[scenario][estimate]") {
  // Each link 6 * 10^8 s: one transfer over one of them is within what --force allows, over
  // both it is not.
  const std::string links = R"(
[[links]]
name = "a"
bandwidth = "1 GB/s"
latency = "6e8 s"
[[links]]
name = "b"
bandwidth = "1 GB/s"
latency = "6e8 s"
[[routes]]
hosts = ["node", "storage"]
links = [{}]
)";
  const std::string one = remote_reader(fmt::format(fmt::runtime(links), "\"a\""), 1);
  CHECK(run_scenario(parse_scenario(one, "s.toml", {}, {}, ScenarioLimits::forced())).summary.makespan >= 6e8);
  const std::string both = remote_reader(fmt::format(fmt::runtime(links), "\"a\", \"b\""), 1);
  CHECK_THAT(error_of(both, ScenarioLimits::forced()),
             Catch::StartsWith("s.toml:24:11: key 'links[0].latency': the run would take at least about 1.2e+09 s"));
}

}  // namespace
}  // namespace pagecache
