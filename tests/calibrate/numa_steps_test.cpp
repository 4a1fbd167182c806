// calibrate's NUMA step on this machine against a fake two-node topology, with a fake binding
// that records what it is asked and binds nothing: where it places the thread and the memory
// for each local/remote pair, the ratios it writes, and what it says with one node or when a
// placement is refused. The fake probes' figures depend on where the binding put the memory
// (node 1's slower by known factors), so a step that mixed local and remote up gives the
// inverse ratio, and one that placed a buffer wrongly is seen in what the probes record.
#include "calibrate/numa_steps.hpp"

#include "calibrate/fake_node_tree.hpp"
#include "calibrate/notes.hpp"

#include <pagecache/scenario_file.hpp>

#include <catch2/catch.hpp>
#include <fmt/format.h>
#include <toml++/toml.h>

#include <cerrno>
#include <chrono>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

using namespace pagecache;
using namespace pagecache::calibrate;
namespace fs = std::filesystem;

namespace {

// Records what it is asked and binds nothing; says where the thread and its memory would be.
class FakeBinding final : public NodeBinding {
 public:
  std::vector<std::string> calls;
  int thread_node = -1;
  int memory_node = -1;
  int refused_node = -1;  ///< allocate_on it throws, as a set_mempolicy a seccomp profile forbids

  int run_on(const NumaNode& node) override {
    calls.push_back(fmt::format("run_on {}", node.id));
    thread_node = node.id;
    return static_cast<int>(node.cpus.size());
  }
  void allocate_on(int node) override {
    calls.push_back(fmt::format("allocate_on {}", node));
    if (node == refused_node) throw BindingError(EPERM, fmt::format("set_mempolicy(MPOL_BIND) to node {}", node));
    memory_node = node;
  }
  std::string release() noexcept override {
    calls.push_back("release");
    thread_node = memory_node = -1;
    return "";
  }
};

// Figures as a machine would give them where the binding put the memory: node 1's memory
// slower (or faster) by the factors, node 0's at the base rates.
struct FakeMachine {
  FakeBinding& binding;
  double copy_factor = 0.62, touch_factor = 0.625, read_factor = 0.47;
  std::vector<std::string> seen{};          ///< where each probe found the thread and the memory
  std::map<std::string, int> file_nodes{};  ///< where each cached file's pages went

  Figure rate(double base, double factor, int node) const { return Figure{base * (node == 1 ? factor : 1.0), "fake", true}; }

  NumaProbes probes() {
    return NumaProbes{
        [this](const std::function<void()>& source, const std::function<void()>& destination) {
          source();
          const int from = binding.memory_node;
          destination();
          seen.push_back(fmt::format("copy: thread on {}, from {} into {}", binding.thread_node, from, binding.memory_node));
          return rate(10e9, copy_factor, from);
        },
        [this] {
          seen.push_back(fmt::format("first touch: thread on {}, memory on {}", binding.thread_node, binding.memory_node));
          return rate(3e9, touch_factor, binding.memory_node);
        },
        [this](const fs::path& file) {
          file_nodes[file.filename().string()] = binding.memory_node;
          seen.push_back(fmt::format("cache {}: memory on {}", file.filename().string(), binding.memory_node));
        },
        [this](const fs::path& file, int threads) {
          const int pages = file_nodes.at(file.filename().string());
          seen.push_back(fmt::format("read {}: {} threads on {}, buffers on {}", file.filename().string(), threads, binding.thread_node,
                                     binding.memory_node));
          return rate(20e9, read_factor, pages);
        }};
  }
};

// What a step is given, at tiny sizes (a test's time, not a measurement's).
struct Bench {
  Options options;
  SystemInfo sys;
  Budget budget;
  Scratch scratch{fs::temp_directory_path(), "pcsim-numa-test"};
  Session session{options, sys, budget, scratch, std::chrono::steady_clock::now(), 0, 1};
  Calibration c;
  std::vector<std::string> steps;  ///< the steps announced

  Bench() {
    options.quick = true;
    options.progress = [this](const std::string& step, int, int) { steps.push_back(step); };
    sys.memory_available = 64LL << 20;
    budget.repeat = 1;
    budget.memory_seconds = 0.01;
    budget.cache_file = 1LL << 20;
    budget.chunk = 256LL << 10;
    c.date = "2026-12-03T12:00:00Z";
    c.system.hostname = "node-7";
    c.system.memory_total = 16LL << 30;
  }
};

// Node 0 and node 1 with `cpus1` CPUs on node 1.
NumaTopology two_nodes(const FakeNodeTree& tree, const std::string& cpus1 = "2-3,6-7\n") {
  tree.write("online", "0-1\n");
  tree.write("node0/cpulist", "0-1,4-5\n");
  tree.write("node1/cpulist", cpus1);
  return read_numa_topology(tree.root);
}

double toml_ratio(const std::string& platform, const char* key) {
  const toml::table t = toml::parse(platform);
  return t["hosts"][0]["numa"][key].value_or(-1.0);
}

}  // namespace

TEST_CASE("calibrate measures each NUMA ratio with the thread on node 0 and the memory on node 1 over node 0", "[calibrate][numa]") {
  const FakeNodeTree tree;
  Bench b;
  b.c.numa.topology = two_nodes(tree);
  FakeBinding binding;
  FakeMachine machine{binding};
  measure_numa(b.c, b.session, binding, machine.probes());
  const NumaFigures& n = b.c.numa;
  REQUIRE(n.measured);
  CHECK(b.steps == std::vector<std::string>{"memory: node 0's and node 1's, from node 0's CPUs"});
  CHECK(n.local == 0);
  CHECK(n.remote == 1);
  CHECK(n.threads == 4);  // node 0's CPUs 0-1,4-5
  // The thread on node 0 throughout; each measurement local, then remote; the copy's and the
  // readers' buffers on node 0, the cached file's pages where the pair says.
  CHECK(machine.seen == std::vector<std::string>{
                            "first touch: thread on 0, memory on 0",
                            "first touch: thread on 0, memory on 1",
                            "copy: thread on 0, from 0 into 0",
                            "copy: thread on 0, from 1 into 0",
                            "cache numa-node-0: memory on 0",
                            "read numa-node-0: 4 threads on 0, buffers on 0",
                            "cache numa-node-1: memory on 1",
                            "read numa-node-1: 4 threads on 0, buffers on 0",
                        });
  CHECK(binding.calls.front() == "run_on 0");
  CHECK(binding.calls.back() == "release");
  // remote / local of what the probes gave: 6.2 / 10, 1.875 / 3, 9.4 / 20 GB/s.
  CHECK(n.copy.ratio() == Approx(0.62));
  CHECK(n.first_touch.ratio() == Approx(0.625));
  CHECK(n.aggregate_read.ratio() == Approx(0.47));
  const std::string platform = platform_toml(b.c);
  INFO(platform);
  CHECK_THAT(platform, Catch::Contains("\n[hosts.numa]\n") && Catch::Contains("\nnodes = 2\n") &&
                           Catch::Contains("\nremote_copy_ratio = 0.620\n") && Catch::Contains("\nremote_first_touch_ratio = 0.625\n") &&
                           Catch::Contains("\nremote_aggregate_ratio = 0.470\n") &&
                           Catch::Contains("# one thread on node 0's CPUs copying memory on node 1 or 0 into a buffer on node 0: remote / local\n") &&
                           Catch::Contains("#   remote, node 1: 6200 MB/s: fake\n#   local, node 0: 10000 MB/s: fake\n") &&
                           Catch::Contains("# 4 threads on node 0's CPUs reading a cached file whose pages are on node 1 or 0"));
  // A TOML reader finds them in the host's table.
  const toml::table t = toml::parse(platform);
  CHECK(t["hosts"][0]["numa"]["nodes"].value_or(0) == 2);
  CHECK(toml_ratio(platform, "remote_copy_ratio") == Approx(0.62));
  CHECK(toml_ratio(platform, "remote_first_touch_ratio") == Approx(0.625));
  CHECK(toml_ratio(platform, "remote_aggregate_ratio") == Approx(0.47));
  CHECK(numa_notes(n).empty());
  // pcsim reads the section (in a host of its own: the fake measured nothing else).
  const std::size_t at = platform.find("\n[hosts.numa]\n");
  const std::string section = platform.substr(at, platform.find("\n[", at + 1) - at);
  const Scenario s = parse_scenario("[pipelines]\ncount = 1\nfile_size = \"1 MB\"\ntasks = 1\n[[hosts]]\nname = \"h\"\nmemory = \"1 GB\"\n"
                                    "memory_read_bw = \"1 GB/s\"\nmemory_write_bw = \"1 GB/s\"\n[[hosts.disks]]\nname = \"d\"\n"
                                    "read_bw = \"1 GB/s\"\nwrite_bw = \"1 GB/s\"" + section,
                                    "platform.toml");
  CHECK(s.hosts[0].numa.nodes == 2);
  CHECK(s.hosts[0].numa.remote.copy == Approx(0.62));
  CHECK(s.hosts[0].numa.remote.first_touch == Approx(0.625));
  CHECK(s.hosts[0].numa.remote.aggregate == Approx(0.47));
}

TEST_CASE("calibrate writes a NUMA ratio above 1 as measured, with a note", "[calibrate][numa]") {
  const FakeNodeTree tree;
  Bench b;
  b.c.numa.topology = two_nodes(tree, "2-3\n");  // 2 CPUs on node 1 against node 0's 4
  FakeBinding binding;
  FakeMachine machine{binding};
  machine.copy_factor = 1.25;
  measure_numa(b.c, b.session, binding, machine.probes());
  REQUIRE(b.c.numa.measured);
  const std::string platform = platform_toml(b.c);
  INFO(platform);
  CHECK_THAT(platform, Catch::Contains("#   above 1: written as measured (see the notes)\nremote_copy_ratio = 1.250\n"));
  CHECK(toml_ratio(platform, "remote_copy_ratio") == Approx(1.25));
  const std::vector<std::string> notes = numa_notes(b.c.numa);
  REQUIRE(notes.size() == 2);
  CHECK_THAT(notes[0], Catch::StartsWith("remote_copy_ratio is 1.250, above 1: the copy, one thread went faster with node 1's memory") &&
                           Catch::EndsWith("written as measured"));
  CHECK(notes[1] == "the NUMA nodes have unequal CPUs (node 0: 4, node 1: 2); [hosts.numa] splits the cores evenly");
}

TEST_CASE("calibrate runs the NUMA measurements on the first node with CPUs", "[calibrate][numa]") {
  const FakeNodeTree tree;
  tree.write("online", "0-1\n");
  tree.write("node0/cpulist", "\n");  // memory alone
  tree.write("node1/cpulist", "0-3\n");
  Bench b;
  b.c.numa.topology = read_numa_topology(tree.root);
  FakeBinding binding;
  FakeMachine machine{binding};
  measure_numa(b.c, b.session, binding, machine.probes());
  REQUIRE(b.c.numa.measured);
  CHECK(b.c.numa.local == 1);
  CHECK(b.c.numa.remote == 0);
  CHECK(binding.calls.front() == "run_on 1");
  CHECK(machine.seen.at(1) == "first touch: thread on 1, memory on 0");
}

TEST_CASE("calibrate on more nodes than pcsim models measures, notes the ratios and writes no [hosts.numa]", "[calibrate][numa]") {
  const FakeNodeTree tree;
  tree.write("online", "0-2\n");
  tree.write("node0/cpulist", "0-1\n");
  tree.write("node1/cpulist", "2-3\n");
  tree.write("node2/cpulist", "4-5\n");
  Bench b;
  b.c.numa.topology = read_numa_topology(tree.root);
  FakeBinding binding;
  FakeMachine machine{binding};
  measure_numa(b.c, b.session, binding, machine.probes());
  REQUIRE(b.c.numa.measured);
  add_notes(b.c);
  const std::string platform = platform_toml(b.c);
  INFO(platform);
  CHECK_THAT(platform, !Catch::Contains("\n[hosts.numa]") &&
                           Catch::Contains("3 NUMA nodes: pcsim models at most 2, so the platform has no [hosts.numa]; the ratios measured "
                                           "between node 0 and node 1"));
  CHECK_FALSE(toml::parse(platform)["hosts"][0]["numa"]);
}

TEST_CASE("calibrate with one NUMA node says so and writes no [hosts.numa]", "[calibrate][numa]") {
  Bench b;
  b.c.numa.topology = read_numa_topology(fs::temp_directory_path() / "pcsim-no-such-node-folder");
  FakeBinding binding;
  FakeMachine machine{binding};
  measure_numa(b.c, b.session, binding, machine.probes());
  CHECK_FALSE(b.c.numa.measured);
  CHECK(binding.calls.empty());
  CHECK(machine.seen.empty());
  CHECK(b.steps.empty());  // no step announced
  CHECK(b.c.numa.why == "one NUMA node: no remote memory to measure; the platform has no [hosts.numa]");
  add_notes(b.c);
  CHECK(std::count(b.c.notes.begin(), b.c.notes.end(), std::string(kOneNumaNode)) == 1);
  const std::string platform = platform_toml(b.c);
  INFO(platform);
  CHECK_THAT(platform, Catch::Contains("# Note: one NUMA node: no remote memory to measure; the platform has no [hosts.numa]\n") &&
                           !Catch::Contains("\n[hosts.numa]") && !Catch::Contains("remote_"));
  CHECK_FALSE(toml::parse(platform)["hosts"][0]["numa"]);
}

TEST_CASE("calibrate leaves [hosts.numa] out and says which system call failed when a placement is refused", "[calibrate][numa]") {
  const FakeNodeTree tree;
  Bench b;
  b.c.numa.topology = two_nodes(tree);
  FakeBinding binding;
  binding.refused_node = 1;
  FakeMachine machine{binding};
  measure_numa(b.c, b.session, binding, machine.probes());
  CHECK_FALSE(b.c.numa.measured);
  CHECK(binding.calls.back() == "release");  // undone, also on the error
  CHECK_THAT(b.c.numa.why, Catch::Contains("set_mempolicy(MPOL_BIND) to node 1: Operation not permitted") &&
                               Catch::EndsWith("the platform has no [hosts.numa]"));
  CHECK(numa_notes(b.c.numa) == std::vector<std::string>{b.c.numa.why});
  CHECK_THAT(platform_toml(b.c), !Catch::Contains("\n[hosts.numa]"));
}

TEST_CASE("calibrate's own NUMA probes run the memory steps' measurements where the binding placed them", "[calibrate][numa]") {
  // The real copy, first touch, cached file and reads at tiny sizes; the fake binds nothing, so
  // both "nodes" are this machine's one and no ratio is judged.
  const FakeNodeTree tree;
  Bench b;
  b.c.numa.topology = two_nodes(tree);
  FakeBinding binding;
  measure_numa(b.c, b.session, binding, numa_probes(b.session, 2));
  const NumaFigures& n = b.c.numa;
  REQUIRE(n.measured);
  for (const NumaKey& k : kNumaKeys) {
    INFO(k.key);
    CHECK((n.*k.pair).measured());
    CHECK((n.*k.pair).ratio() > 0.0);
  }
  CHECK_THAT(n.copy.local.how, Catch::StartsWith("memcpy of 32 MiB, one thread"));
  CHECK_THAT(n.aggregate_read.remote.how, Catch::StartsWith("read() of cached data into reused buffers, 4 threads at once"));
  CHECK(binding.calls == std::vector<std::string>{"run_on 0", "allocate_on 0", "allocate_on 1",                         // first touch
                                                  "allocate_on 0", "allocate_on 0", "allocate_on 1", "allocate_on 0",  // copy
                                                  "allocate_on 0", "allocate_on 0", "allocate_on 1", "allocate_on 0",  // reads
                                                  "release"});
  CHECK(fs::is_empty(b.scratch.file("x").parent_path()));  // the cached files removed
  const std::string platform = platform_toml(b.c);
  for (const NumaKey& k : kNumaKeys) CHECK_THAT(platform, Catch::Contains(fmt::format("\n{} = ", k.key)));
}
