// run_scenario on scenarios built in code, which skip the loader's checks.

#include <pagecache/error.hpp>
#include <pagecache/run.hpp>
#include <pagecache/scenario.hpp>

#include <catch2/catch.hpp>

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

TEST_CASE("run_scenario runs a scenario built in code", "[run]") {
  const RunResult r = run_scenario(one_pipeline());
  CHECK(r.summary.read.bytes == 300'000'000);
  CHECK(r.summary.write.bytes == 300'000'000);
  CHECK(r.timeline.size() == 3);
}

TEST_CASE("the cache contents name their I/O phase by its timeline row and their file by its index", "[run]") {
  // One task reads file_1 (300 MB, not cached), computes, writes file_2: after the read, all
  // of file_1 is cached and none of file_2; after the write, both (4 GB of memory hold them).
  const RunResult r = run_scenario(one_pipeline());
  REQUIRE(r.files == std::vector<std::string>{"file_1", "file_2"});
  REQUIRE(r.cache.size() == 4);  // two files after each of the two I/O phases
  const auto phase = [&](std::size_t i) { return r.timeline.at(r.cache[i].phase).phase; };
  CHECK(phase(0) == "read");
  CHECK(phase(2) == "write");
  CHECK(r.timeline.at(r.cache[0].phase).task == "1");
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
  CHECK_THROWS_WITH(run_scenario(unlinked), Catch::Contains("no link joins it to host 'node'"));
}

TEST_CASE("run_scenario rejects a workflow with two tasks of one name or an unknown predecessor", "[run][errors]") {
  Scenario s = one_pipeline();
  WorkflowSpec w;
  w.name = "flow";
  w.host = "node";
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

}  // namespace
}  // namespace pagecache
