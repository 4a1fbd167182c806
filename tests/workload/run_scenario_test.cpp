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

TEST_CASE("run_scenario rejects two files of one name and a task naming an unknown file", "[run][errors]") {
  Scenario twice = one_pipeline();
  twice.files.push_back(twice.files.front());
  CHECK_THROWS_WITH(run_scenario(twice), Catch::Contains("two files named 'file_1'"));

  Scenario unknown = one_pipeline();
  unknown.apps.front().tasks.front().writes.push_back("nowhere");
  CHECK_THROWS_AS(run_scenario(unknown), ConfigError);
  CHECK_THROWS_WITH(run_scenario(unknown), Catch::Contains("no file named 'nowhere'"));
}

}  // namespace
}  // namespace pagecache
