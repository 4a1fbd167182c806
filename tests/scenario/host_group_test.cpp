// Host groups: a [[hosts]] table with `count` is that many hosts alike, a link naming the group
// one link per member, and pipelines on the group spread over its members.

#include <pagecache/error.hpp>
#include <pagecache/run.hpp>
#include <pagecache/scenario.hpp>
#include <pagecache/scenario_file.hpp>

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <string>

namespace pagecache {
namespace {

std::string cluster(const std::string& group, const std::string& link_ends, const std::string& pipelines) {
  return R"(
profile = "linux"
[[hosts]]
name = "node"
)" + group + R"(
cores = 2
memory = "4 GB"
memory_read_bw = "6 GB/s"
memory_write_bw = "3 GB/s"
[[hosts.disks]]
name = "ssd"
read_bw = "500 MB/s"
write_bw = "500 MB/s"

[[hosts]]
name = "storage"
memory = "16 GB"
memory_read_bw = "6 GB/s"
memory_write_bw = "3 GB/s"
[hosts.page_cache]
mode = "writethrough"
[[hosts.disks]]
name = "nfs-disk"
read_bw = "500 MB/s"
write_bw = "400 MB/s"

[[links]]
name = "net"
bandwidth = "1 GB/s"
hosts = )" + link_ends + R"(

[pipelines]
file_size = "100 MB"
tasks = 1
chunk_size = "10 MB"
)" + pipelines;
}

TEST_CASE("a host group is that many hosts, each with its own link and its share of the pipelines", "[scenario][host_group]") {
  const Scenario s = parse_scenario(cluster("count = 3", R"(["node", "storage"])", "count = 7\nhost = \"node\"\nfiles_host = \"storage\""), "group");
  REQUIRE(s.hosts.size() == 4);
  CHECK(s.hosts[0].name == "node-1");
  CHECK(s.hosts[2].name == "node-3");
  CHECK(s.hosts[2].cores == 2);
  CHECK(s.hosts[3].name == "storage");
  REQUIRE(s.links.size() == 3);
  CHECK(s.links[1].name == "net-2");
  CHECK(s.links[1].host_a == "node-2");
  CHECK(s.links[1].host_b == "storage");
  REQUIRE(s.apps.size() == 7);
  // In blocks: 7 pipelines over 3 members, 3 + 2 + 2.
  const std::vector<std::string> expected = {"node-1", "node-1", "node-1", "node-2", "node-2", "node-3", "node-3"};
  for (std::size_t i = 0; i < s.apps.size(); ++i) CHECK(s.apps[i].host == expected[i]);
  for (const FileSpec& f : s.files) CHECK(f.host == "storage");

  // Each member is a host of its own: the same run as its hosts, links and applications written
  // out one by one.
  std::string by_hand = R"(
profile = "linux"
)";
  for (int k = 1; k <= 3; ++k) {
    by_hand += fmt::format(R"(
[[hosts]]
name = "node-{0}"
cores = 2
memory = "4 GB"
memory_read_bw = "6 GB/s"
memory_write_bw = "3 GB/s"
[[hosts.disks]]
name = "ssd"
read_bw = "500 MB/s"
write_bw = "500 MB/s"
)", k);
  }
  by_hand += R"(
[[hosts]]
name = "storage"
memory = "16 GB"
memory_read_bw = "6 GB/s"
memory_write_bw = "3 GB/s"
[hosts.page_cache]
mode = "writethrough"
[[hosts.disks]]
name = "nfs-disk"
read_bw = "500 MB/s"
write_bw = "400 MB/s"
)";
  for (int k = 1; k <= 3; ++k) by_hand += fmt::format("[[links]]\nname = \"net-{0}\"\nbandwidth = \"1 GB/s\"\nhosts = [\"node-{0}\", \"storage\"]\n", k);
  for (int i = 1; i <= 7; ++i) {
    by_hand += fmt::format("[[files]]\nname = \"p{0}_file_1\"\nsize = \"100 MB\"\nhost = \"storage\"\n[[files]]\nname = \"p{0}_file_2\"\nsize = \"100 MB\"\nhost = \"storage\"\n", i);
  }
  for (int i = 1; i <= 7; ++i) {
    by_hand += fmt::format("[[apps]]\nname = \"{0}\"\nhost = \"{1}\"\nchunk_size = \"10 MB\"\n[[apps.tasks]]\nname = \"1\"\nread = \"p{0}_file_1\"\nwrite = \"p{0}_file_2\"\n", i, expected[static_cast<std::size_t>(i - 1)]);
  }
  const RunResult grouped = run_scenario(s);
  const RunResult written = run_scenario(parse_scenario(by_hand, "by hand"));
  CHECK(grouped.summary.makespan > 1.0);
  CHECK(grouped.summary.makespan == written.summary.makespan);
  REQUIRE(grouped.timeline.size() == written.timeline.size());
  for (std::size_t i = 0; i < grouped.timeline.size(); ++i) {
    CHECK(grouped.timeline[i].start == written.timeline[i].start);
    CHECK(grouped.timeline[i].end == written.timeline[i].end);
  }
}

TEST_CASE("host groups refuse what they cannot mean", "[scenario][host_group]") {
  const auto fails = [](const std::string& text, const std::string& message) {
    CHECK_THROWS_WITH(parse_scenario(text, "bad"), Catch::Contains(message));
  };
  fails(cluster("count = 0", R"(["node", "storage"])", "host = \"node\"\nfiles_host = \"storage\""), "count");
  fails(cluster("count = 1000000000", R"(["node", "storage"])", "host = \"node\"\nfiles_host = \"storage\""), "count");
  // Within the loader's bound, but more hosts than a run may have (each costs it about 24 kB):
  // refused at the group's count, the hosts so far and its own, before a member is made.
  fails(cluster("count = 30000", R"(["node", "storage"])", "host = \"node\"\nfiles_host = \"storage\""),
        "key 'hosts[0].count': 30000 hosts, more than the 20000 a run may have without --force");
  fails(cluster("count = 2", R"(["node", "storage"])", "host = \"node\""), "'node' is a host group: the pipelines' files are on one host");
  fails(cluster("count = 2", R"(["node", "storage"])", "host = \"node-3\"\nfiles_host = \"storage\""), "no host named 'node-3'");
  fails(cluster("count = 2", R"(["node", "nowhere"])", "host = \"node\"\nfiles_host = \"storage\""), "no host named 'nowhere'");
}

}  // namespace
}  // namespace pagecache
