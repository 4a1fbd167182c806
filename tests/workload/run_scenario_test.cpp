// run_scenario on scenarios built in code, which skip the loader's checks.

#include <pagecache/error.hpp>
#include <pagecache/run.hpp>
#include <pagecache/scenario.hpp>
#include <pagecache/scenario_file.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <string>
#include <vector>

namespace pagecache {
namespace {

Scenario one_pipeline() {
  return parse_scenario(R"(
[[hosts]]
name = "node"
cores = 1
memory = "4 GB"
memory_read_bw = "6 GB/s"
memory_write_bw = "3 GB/s"
[[hosts.disks]]
name = "disk"
read_bw = "500 MB/s"
write_bw = "400 MB/s"
[pipelines]
count = 1
file_size = "300 MB"
tasks = 1
)",
                        "<test>");
}

// The sizes the README quotes for what a run keeps per phase and per file after a phase.
static_assert(sizeof(PhaseRow) == 56, "README: a timeline row of 56 bytes");
static_assert(sizeof(CacheRow) == 16, "README: 16 bytes per file after each I/O phase");

TEST_CASE("run_scenario runs a scenario built in code", "[run]") {
  const RunResult r = run_scenario(one_pipeline());
  CHECK(r.summary.read.bytes == 300'000'000);
  CHECK(r.summary.write.bytes == 300'000'000);
  CHECK(r.timeline.size() == 3);
}

// Applications (with deletes, fsync and a memory group), pipelines and a workflow in one run.
Scenario apps_and_workflow() {
  return parse_scenario(R"(
memory_sample_interval = "0 s"
[[hosts]]
name = "node"
cores = 2
memory = "4 GB"
memory_read_bw = "6 GB/s"
memory_write_bw = "3 GB/s"
[[hosts.disks]]
name = "disk"
read_bw = "500 MB/s"
write_bw = "400 MB/s"
[[files]]
name = "a"
size = "500 MB"
[[files]]
name = "b"
size = "300 MB"
[[files]]
name = "c"
size = "200 MB"
[[apps]]
name = "writer"
memory_max = "2 GB"
[[apps.tasks]]
name = "copy"
read = "a"
compute = "1 s"
write = "b"
fsync = true
[[apps.tasks]]
name = "drop"
read = "b"
delete = "b"
[pipelines]
count = 2
file_size = "200 MB"
tasks = 2
[workflow]
name = "wf"
[[workflow.tasks]]
name = "first"
read = "a"
write = "c"
[[workflow.tasks]]
name = "second"
read = "c"
compute = "0.5 s"
)",
                        "<test>");
}

// Two runs' results, but for the wall time.
void require_same_results(const RunResult& a, const RunResult& b) {
  REQUIRE(a.timeline.size() == b.timeline.size());
  for (std::size_t i = 0; i < a.timeline.size(); ++i) {
    const PhaseRow& x = a.timeline[i];
    const PhaseRow& y = b.timeline[i];
    INFO("timeline row " << i);
    CHECK(a.app_name(x) == b.app_name(y));
    CHECK(a.task_name(x) == b.task_name(y));
    CHECK(x.phase == y.phase);
    CHECK(x.start == y.start);
    CHECK(x.end == y.end);
    CHECK(x.bytes == y.bytes);
    CHECK(x.cache_bytes == y.cache_bytes);
    CHECK(x.disk_bytes == y.disk_bytes);
  }
  REQUIRE(a.memory.size() == b.memory.size());
  for (std::size_t i = 0; i < a.memory.size(); ++i) {
    INFO("memory row " << i);
    CHECK(a.host_name(a.memory[i]) == b.host_name(b.memory[i]));
    CHECK(a.memory[i].time == b.memory[i].time);
    CHECK(a.memory[i].state == b.memory[i].state);
  }
  CHECK(a.files == b.files);
  REQUIRE(a.cache.size() == b.cache.size());
  for (std::size_t i = 0; i < a.cache.size(); ++i) {
    INFO("cache row " << i);
    CHECK(a.cache[i].phase == b.cache[i].phase);
    CHECK(a.cache[i].file == b.cache[i].file);
    CHECK(a.cache[i].cached == b.cache[i].cached);
  }
  CHECK(a.summary.makespan == b.summary.makespan);
  CHECK(a.summary.end_time == b.summary.end_time);
  CHECK(a.summary.events == b.summary.events);
  CHECK(a.summary.evicted_bytes == b.summary.evicted_bytes);
  CHECK(a.summary.forced_flush_bytes == b.summary.forced_flush_bytes);
  CHECK(a.summary.periodic_flush_bytes == b.summary.periodic_flush_bytes);
}

TEST_CASE("a scenario handed over to run_scenario runs as one its caller keeps", "[run]") {
  // The run frees the applications and files of a scenario it is given, once planned: what it
  // runs from must be its own copies.
  std::vector<std::pair<std::string, Scenario>> cases;
  cases.emplace_back("apps, pipelines and a workflow", apps_and_workflow());
  for (const char* path : {"scenarios/examples/memory-limit.toml", "scenarios/examples/nighres-over-nfs.toml",
                           "scenarios/examples/file-no-longer-fits.toml", "tests/apps/golden/small_workflow.toml"}) {
    cases.emplace_back(path, load_scenario(std::string(PCSIM_SOURCE_DIR) + "/" + path));
  }
  for (const auto& [name, scenario] : cases) {
    INFO(name);
    const RunResult kept = run_scenario(scenario);
    REQUIRE_FALSE(kept.timeline.empty());
    Scenario given = scenario;
    const RunResult handed_over = run_scenario(std::move(given));
    require_same_results(kept, handed_over);
  }
}

TEST_CASE("the cache contents name their I/O phase by its timeline row and their file by its index", "[run]") {
  // One task reads file_1 (300 MB, not cached), computes, writes file_2: after the read, all
  // of file_1 is cached and none of file_2; after the write, both (4 GB of memory hold them).
  const RunResult r = run_scenario(one_pipeline());
  REQUIRE(r.files == std::vector<std::string>{"file_1", "file_2"});
  REQUIRE(r.cache.size() == 4);  // two files after each of the two I/O phases
  const auto phase = [&](std::size_t i) { return r.timeline.at(r.cache[i].phase).phase; };
  CHECK(phase(0) == PhaseKind::Read);
  CHECK(phase(2) == PhaseKind::Write);
  CHECK(r.task_name(r.timeline.at(r.cache[0].phase)) == "1");
  CHECK(r.cache[0].file == 0);
  CHECK(r.cache[1].file == 1);
  CHECK(r.cache[0].cached == 300'000'000);
  CHECK(r.cache[1].cached == 0);
  CHECK(r.cache[2].cached == 300'000'000);
  CHECK(r.cache[3].cached == 300'000'000);

  RunOptions off;
  off.cache_contents = false;
  const RunResult none = run_scenario(one_pipeline(), off);
  CHECK(none.cache.empty());
  CHECK(none.files.empty());
  CHECK(none.cache_not_recorded == "switched off");
}

TEST_CASE("run_scenario rejects two files of one name and a task naming an unknown file", "[run][errors]") {
  Scenario twice = one_pipeline();
  twice.files.push_back(twice.files.front());
  CHECK_THROWS_WITH(run_scenario(twice), Catch::Contains("two files named 'file_1'"));

  Scenario unknown = one_pipeline();
  unknown.apps.front().tasks.front().writes.push_back("nowhere");
  CHECK_THROWS_AS(run_scenario(unknown), ConfigError);
  CHECK_THROWS_WITH(run_scenario(unknown), Catch::Contains("no file named 'nowhere'"));
}

TEST_CASE("run_scenario rejects unknown hosts, unknown disks and remote files without a link", "[run][errors]") {
  Scenario app_host = one_pipeline();
  app_host.apps.front().host = "elsewhere";
  CHECK_THROWS_WITH(run_scenario(app_host), Catch::Contains("application '1': no host named 'elsewhere'"));

  Scenario file_disk = one_pipeline();
  file_disk.files.front().disk = "tape";
  CHECK_THROWS_WITH(run_scenario(file_disk), Catch::Contains("host 'node' has no disk named 'tape'"));

  Scenario unlinked = one_pipeline();
  HostConfig server = unlinked.hosts.front();
  server.name = "server";
  unlinked.hosts.push_back(server);
  unlinked.files.front().host = "server";
  CHECK_THROWS_AS(run_scenario(unlinked), ConfigError);
  CHECK_THROWS_WITH(run_scenario(unlinked), Catch::Contains("no route joins it to host 'node'"));
}

TEST_CASE("run_scenario rejects a workflow with two tasks of one name or an unknown predecessor", "[run][errors]") {
  Scenario s = one_pipeline();
  WorkflowSpec w;
  w.name = "flow";
  w.hosts = {"node"};
  for (const char* name : {"a", "b"}) {
    TaskSpec& task = w.tasks.emplace_back();
    task.name = name;
    task.reads = {"file_1"};
    task.chunk_size = 100'000'000;
  }
  s.apps.clear();

  Scenario twice = s;
  twice.workflows.push_back(w);
  twice.workflows.back().tasks.back().name = "a";
  CHECK_THROWS_WITH(run_scenario(twice), Catch::Contains("workflow 'flow': two tasks named 'a'"));

  Scenario unknown = s;
  unknown.workflows.push_back(w);
  unknown.workflows.back().tasks.back().after = {"z"};
  CHECK_THROWS_WITH(run_scenario(unknown), Catch::Contains("task 'b' comes after an unknown task 'z'"));
}

TEST_CASE("workflow tasks run in memory groups of their own, from the workflow's limits or their own", "[run][groups]") {
  // Task a (the workflow's memory_max, 1.5 GB) reads its 1 GB input in 100 MB chunks and
  // holds the buffers: as host_groups_test derives, its group keeps 500 MB of the file cached
  // (1 GB of buffers + 500 MB). Task b, after a, has its own 3 GB: its 1 GB input and 1 GB of
  // buffers fit, all of it stays cached. The 4 GB host never runs short. Without limits both
  // inputs stay whole. show names the limits; a task's memory_high above its memory_max is
  // refused by key.
  const std::string text = R"(
[[hosts]]
name = "node"
cores = 1
memory = "4 GB"
memory_read_bw = "6 GB/s"
memory_write_bw = "3 GB/s"
[[hosts.disks]]
name = "disk"
read_bw = "500 MB/s"
write_bw = "400 MB/s"
[[files]]
name = "in_a"
size = "1 GB"
[[files]]
name = "in_b"
size = "1 GB"
[workflow]
memory_max = "1.5 GB"
[[workflow.tasks]]
name = "a"
read = "in_a"
[[workflow.tasks]]
name = "b"
read = "in_b"
after = ["a"]
memory_max = "3 GB"
)";
  for (const bool limited : {true, false}) {
    std::string scenario = text;
    if (!limited) {
      for (const std::string key : {"memory_max = \"1.5 GB\"\n", "memory_max = \"3 GB\"\n"}) scenario.erase(scenario.find(key), key.size());
    }
    const RunResult r = run_scenario(parse_scenario(scenario, "<test>"));
    INFO("limited " << limited);
    REQUIRE(r.files == std::vector<std::string>{"in_a", "in_b"});
    // The cached bytes of a file after the read phase of a task.
    const auto cached_after_read = [&](const std::string& task, std::size_t file) {
      for (const auto& row : r.cache) {
        if (row.file == file && r.task_name(r.timeline.at(row.phase)) == task && r.timeline.at(row.phase).phase == PhaseKind::Read) return row.cached;
      }
      FAIL("no cache row for task " << task);
      return std::int64_t{-1};
    };
    CHECK(cached_after_read("a", 0) == (limited ? 500'000'000 : 1'000'000'000));
    CHECK(cached_after_read("b", 1) == 1'000'000'000);
    CHECK(cached_after_read("b", 0) == (limited ? 500'000'000 : 1'000'000'000));
  }
  const Scenario s = parse_scenario(text, "<test>");
  CHECK(s.workflows.at(0).tasks.at(0).memory_limits.max == 1'500'000'000);
  CHECK(s.workflows.at(0).tasks.at(1).memory_limits.max == 3'000'000'000);
  std::string high = text;
  const std::string own = "memory_max = \"3 GB\"";
  high.replace(high.find(own), own.size(), own + "\nmemory_high = \"4 GB\"");
  CHECK_THROWS_WITH(parse_scenario(high, "<test>"), Catch::Contains("workflow.tasks[1]") && Catch::Contains("memory_high"));
}

// One pipeline on a node whose files are on a server across a link, so that two hosts' memory
// is sampled: 300 MB read from the server (0.6 s at its disk's 500 MB/s), `compute` seconds of
// CPU, 300 MB written back over the link, in 10 MB chunks. Times are not multiples of the
// 0.25 s interval.
Scenario remote_pipeline(const std::string& compute, const std::string& interval) {
  return parse_scenario(R"(
memory_sample_interval = ")" + interval + R"("
[[hosts]]
name = "node"
memory = "4 GB"
memory_read_bw = "6 GB/s"
memory_write_bw = "3 GB/s"
[[hosts.disks]]
name = "disk"
read_bw = "500 MB/s"
write_bw = "400 MB/s"
[[hosts]]
name = "server"
memory = "4 GB"
memory_read_bw = "6 GB/s"
memory_write_bw = "3 GB/s"
[[hosts.disks]]
name = "disk"
read_bw = "500 MB/s"
write_bw = "400 MB/s"
[[links]]
bandwidth = "700 MB/s"
hosts = ["node", "server"]
[pipelines]
files_host = "server"
file_size = "300 MB"
tasks = 1
chunk_size = "10 MB"
cpu_time = ")" + compute + R"("
)",
                        "<test>");
}

TEST_CASE("memory samples skip the ticks after which nothing changed", "[run][memory]") {
  // A 10^7 s compute with a 0.25 s interval: a sampler ticking through it took 4 * 10^7
  // events. The run's events follow its work.
  const RunResult r = run_scenario(remote_pipeline("1e7 s", "0.25 s"));
  CHECK(r.summary.makespan > 1e7);
  CHECK(r.summary.events < 2'000);
  CHECK(r.memory.size() < 200);
}

TEST_CASE("sampled memory rows are the tick-time states of the every-change profile", "[run][memory]") {
  // The reference: the profile of every change ("0 s"), read at every tick 0, 0.25, ... before
  // the makespan, keeping a host's row when it differs from that host's previous one. The
  // sampler must give exactly those rows (the last rows, after the makespan, aside).
  const RunResult every = run_scenario(remote_pipeline("3000 s", "0 s"));
  const RunResult sampled = run_scenario(remote_pipeline("3000 s", "0.25 s"));
  REQUIRE(every.summary.makespan == sampled.summary.makespan);
  std::vector<MemoryRow> expected;
  REQUIRE(every.hosts == sampled.hosts);
  for (const std::string host : {"node", "server"}) {
    std::vector<const MemoryRow*> changes;
    for (const MemoryRow& m : every.memory)
      if (every.host_name(m) == host) changes.push_back(&m);
    REQUIRE(changes.size() > 10);
    const MemoryState* last = nullptr;
    std::size_t next = 0;
    for (double tick = 0.0; tick < every.summary.makespan; tick += 0.25) {
      while (next < changes.size() && changes[next]->time <= tick) ++next;
      const MemoryState& state = changes[next - 1]->state;
      if (last == nullptr || !(*last == state)) expected.push_back({tick, changes.front()->host, state});
      last = &state;
    }
  }
  std::vector<MemoryRow> got;
  for (const MemoryRow& m : sampled.memory)
    if (m.time < sampled.summary.makespan) got.push_back(m);
  std::stable_sort(expected.begin(), expected.end(), [](const MemoryRow& a, const MemoryRow& b) { return a.time < b.time; });
  REQUIRE(got.size() == expected.size());
  for (std::size_t i = 0; i < got.size(); ++i) {
    INFO("row " << i << " at " << expected[i].time << " s, " << every.host_name(expected[i]));
    CHECK(got[i].time == expected[i].time);
    CHECK(got[i].host == expected[i].host);
    CHECK(got[i].state == expected[i].state);
  }
}

TEST_CASE("a run stops with a SimulationError once its clock passes the limit", "[run][errors]") {
  RunOptions options;
  options.max_simulated_time = 1e5;
  CHECK_THROWS_WITH(run_scenario(remote_pipeline("1e6 s", "0.25 s"), options), Catch::Contains("passed 100000 s"));
}


// A host and two files, `in` and `x`, for a workload reading a deleted file.
std::string with_files(const std::string& workload) {
  return R"(
[[hosts]]
name = "h"
cores = 4
memory = "8 GB"
memory_read_bw = "5 GB/s"
memory_write_bw = "5 GB/s"
[[hosts.disks]]
name = "d"
read_bw = "500 MB/s"
write_bw = "500 MB/s"
[[files]]
name = "in"
size = "100 MB"
[[files]]
name = "x"
size = "100 MB"
)" + workload;
}

std::string load_error(const std::string& text) {
  try {
    parse_scenario(text, "s.toml");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(loaded)";
}

std::string run_error(const Scenario& s) {
  try {
    run_scenario(s);
  } catch (const SimulationError& e) {
    return e.what();
  }
  return "(ran)";
}

TEST_CASE("a read of a deleted file is refused at load when the scenario orders it after the deletion", "[run][errors][delete]") {
  // An application's tasks run one after the other: its third task reads what its second
  // deleted.
  const std::string app = with_files(R"(
[[apps]]
name = "a"
[[apps.tasks]]
name = "make"
read = "in"
write = "x"
[[apps.tasks]]
name = "use"
read = "x"
delete = "x"
[[apps.tasks]]
name = "again"
read = "x"
)");
  CHECK(load_error(app) == "s.toml:31:8: key 'apps[0].tasks[2].read': task 'again' of application 'a' reads file 'x', which its task 'use' "
                           "deleted before (an application's tasks run one after the other)");
  // Written again in between, it is there to read.
  std::string rewritten = app;
  rewritten.insert(rewritten.rfind("[[apps.tasks]]"), "[[apps.tasks]]\nname = \"remake\"\nwrite = \"x\"\n");
  CHECK(run_scenario(parse_scenario(rewritten, "s.toml")).timeline.size() == 12);

  // A workflow task after the deleter (`after`, or through the files it reads), the file's
  // writer before it.
  const std::string workflow = with_files(R"(
[workflow]
name = "wf"
[[workflow.tasks]]
name = "make"
read = "in"
write = "x"
[[workflow.tasks]]
name = "use"
read = "x"
delete = "x"
[[workflow.tasks]]
name = "again"
read = "x"
after = ["use"]
)");
  CHECK_THAT(load_error(workflow), Catch::StartsWith("s.toml:31:8: key 'workflow.tasks[2].read': task 'again' of workflow 'wf' reads file 'x', "
                                                     "which task 'use' deletes before it") &&
                                       Catch::Contains("its writer, 'make', runs before 'use'"));
  // The writer deleting its own output before its reader starts.
  const std::string own = with_files(R"(
[workflow]
name = "wf"
[[workflow.tasks]]
name = "make"
read = "in"
write = "x"
delete = "x"
[[workflow.tasks]]
name = "use"
read = "x"
)");
  CHECK_THAT(load_error(own), Catch::StartsWith("s.toml:28:8: key 'workflow.tasks[1].read': task 'use' of workflow 'wf' reads file 'x', "
                                                "which task 'make' deletes before it"));
}

TEST_CASE("a read of a deleted file that the run's order decides fails the run at its simulated time", "[run][errors][delete]") {
  // Two applications: the second reads x at 5 s, which the first deleted at 0.2 s (read in
  // 0.2 s at the disk's 500 MB/s).
  const Scenario apps = parse_scenario(with_files(R"(
[[apps]]
name = "deleter"
[[apps.tasks]]
name = "drop"
read = "x"
delete = "x"
[[apps]]
name = "late"
[[apps.tasks]]
name = "wait"
compute = "5 s"
[[apps.tasks]]
name = "read"
read = "x"
)"),
                                       "s.toml");
  CHECK(run_error(apps) == "t = 5.000000 s: task 'read' of application 'late' reads file 'x', which task 'drop' of application 'deleter' "
                           "deleted at t = 0.200000 s");
  // A workflow task in no order with the deleter: here it comes after (its own predecessor
  // computes 5 s), so the run fails; the other way round it reads the file before.
  const std::string workflow = with_files(R"(
[workflow]
name = "wf"
[[workflow.tasks]]
name = "make"
read = "in"
write = "x"
[[workflow.tasks]]
name = "use"
read = "x"
delete = "x"
[[workflow.tasks]]
name = "slow"
compute = "5 s"
[[workflow.tasks]]
name = "late"
read = "x"
after = ["slow"]
)");
  CHECK_THAT(run_error(parse_scenario(workflow, "s.toml")),
             Catch::StartsWith("t = 5.000000 s: task 'late' of workflow 'wf' reads file 'x', which task 'use' of workflow 'wf' deleted at t = "));
  std::string early = workflow;
  early.replace(early.find("compute = \"5 s\""), 15, "compute = \"0 s\"");
  CHECK(run_error(parse_scenario(early, "s.toml")) == "(ran)");
  // A file deleted by one application and written again by another is there to read.
  Scenario rewritten = apps;
  TaskSpec& remake = rewritten.apps[1].tasks.insert(rewritten.apps[1].tasks.begin() + 1, TaskSpec{})[0];
  remake.name = "remake";
  remake.writes = {"x"};
  remake.chunk_size = 100'000'000;
  CHECK(run_error(rewritten) == "(ran)");
}

}  // namespace
}  // namespace pagecache
