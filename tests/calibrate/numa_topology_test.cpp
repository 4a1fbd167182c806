// calibrate's reader of the NUMA topology: the kernel's list format, and a fake
// /sys/devices/system/node tree in a temporary folder (good, malformed, absent).
#include "calibrate/numa_topology.hpp"

#include "calibrate/fake_node_tree.hpp"

#include <pagecache/error.hpp>

#include <catch2/catch.hpp>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

using namespace pagecache;
using namespace pagecache::calibrate;
namespace fs = std::filesystem;

namespace {

// The message of what `read` throws.
template <typename Read>
std::string error_of(Read read) {
  try {
    read();
  } catch (const pagecache::Error& e) {
    return e.what();
  }
  return "nothing thrown";
}

}  // namespace

TEST_CASE("calibrate parses the kernel's CPU and node lists strictly", "[calibrate][numa]") {
  CHECK(parse_kernel_list("0-1\n") == std::vector<int>{0, 1});
  CHECK(parse_kernel_list("0") == std::vector<int>{0});
  CHECK(parse_kernel_list("0-2,8,10-11\n") == std::vector<int>{0, 1, 2, 8, 10, 11});
  CHECK(parse_kernel_list("\n").empty());  // a node of memory alone has no CPUs
  CHECK(parse_kernel_list("").empty());
  for (const char* bad : {"0-", "-3", "1,,2", "0,", ",0", "0-1 ", " 0", "a", "0x1", "3-1", "0-3,2", "4,4", "0\n\n", "1:2", "+1", "99999999"}) {
    INFO(bad);
    CHECK_THROWS_AS(parse_kernel_list(bad), std::invalid_argument);
  }
  CHECK(kernel_list_text({0, 1, 2, 8, 10, 11}) == "0-2,8,10-11");
  CHECK(kernel_list_text({}).empty());
}

TEST_CASE("calibrate reads a two-node topology from a sysfs node folder", "[calibrate][numa]") {
  const FakeNodeTree tree;
  tree.write("online", "0-1\n");
  tree.write("possible", "0-3\n");  // not online: not read
  tree.write("node0/cpulist", "0-1,4-5\n");
  tree.write("node1/cpulist", "2-3,6-7\n");
  const NumaTopology t = read_numa_topology(tree.root);
  CHECK(t.online == "0-1");
  REQUIRE(t.nodes.size() == 2);
  CHECK(t.nodes[0].id == 0);
  CHECK(t.nodes[0].cpus == std::vector<int>{0, 1, 4, 5});
  CHECK(t.nodes[1].id == 1);
  CHECK(t.nodes[1].cpus == std::vector<int>{2, 3, 6, 7});
  // Online nodes need not be numbered from 0, and a node may have memory and no CPU.
  tree.write("online", "0,2\n");
  tree.write("node2/cpulist", "\n");
  const NumaTopology gap = read_numa_topology(tree.root);
  REQUIRE(gap.nodes.size() == 2);
  CHECK(gap.nodes[1].id == 2);
  CHECK(gap.nodes[1].cpus.empty());
}

TEST_CASE("calibrate takes a machine without a sysfs node folder as one NUMA node", "[calibrate][numa]") {
  const NumaTopology t = read_numa_topology(fs::temp_directory_path() / "pcsim-no-such-node-folder");
  REQUIRE(t.nodes.size() == 1);
  CHECK(t.nodes[0].id == 0);
  CHECK(t.online.empty());
}

TEST_CASE("calibrate refuses a malformed or incomplete sysfs node folder, naming the file", "[calibrate][numa]") {
  const FakeNodeTree tree;
  const auto read = [&] { read_numa_topology(tree.root); };
  tree.write("node0/cpulist", "0-3\n");  // the folder, without `online`
  CHECK_THAT(error_of(read), Catch::Contains((tree.root / "online").string()) && Catch::Contains("cannot read"));
  tree.write("online", "0-1 2\n");
  CHECK_THAT(error_of(read), Catch::Contains((tree.root / "online").string()) && Catch::Contains("list format") &&
                                 Catch::Contains("'0-1 2' is not a number"));
  tree.write("online", "\n");
  CHECK_THAT(error_of(read), Catch::Contains((tree.root / "online").string()) && Catch::Contains("no node online"));
  tree.write("online", "0-1\n");  // node1 listed online, its folder absent
  CHECK_THAT(error_of(read), Catch::Contains((tree.root / "node1/cpulist").string()) && Catch::Contains("cannot read"));
  tree.write("node1/cpulist", "7-4\n");
  CHECK_THAT(error_of(read), Catch::Contains((tree.root / "node1/cpulist").string()) && Catch::Contains("the range 7-4 goes down"));
  // What each node of this machine gives, read for real: any sysfs this runs on is well formed.
  CHECK_NOTHROW(read_numa_topology());
}
