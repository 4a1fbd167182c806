// NUMA nodes (docs/model.md §6.20): where new memory goes (the toucher's node, then the other,
// no reclaim before), reclaim node by node, the rates of copies with the other node's memory,
// where threads run, and the platform keys. Times are derived in comments.
#include "cache/page_cache.hpp"

#include <pagecache/host.hpp>
#include <pagecache/scenario_file.hpp>

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <deque>
#include <random>
#include <string>
#include <utility>
#include <vector>

using namespace pagecache;
using pagecache::cache::NodeUse;
using pagecache::cache::PageCache;

namespace {

constexpr std::int64_t MB = 1'000'000;

// A host of two nodes of 500 MB; one thread copies at 1000 MB/s, the nodes together at 2000
// MB/s each; first touch free unless given. A remote copy goes at `copy` of the local rate.
HostSpec two_node_host(double copy, double first_touch = 0.0, double first_touch_ratio = 1.0, double aggregate = 1.0) {
  HostSpec spec{.name = "h", .cores = 4, .memory = 1000 * MB, .memory_bandwidth = {1000e6, 1000e6, 4000e6, 4000e6, first_touch, 0.0},
                .cache = CacheSettings::kernel()};
  spec.numa = NumaSpec{.nodes = 2, .remote = NumaRatios{.copy = copy, .first_touch = first_touch_ratio, .aggregate = aggregate}};
  return spec;
}

Task<void> read_on(Simulator& sim, Host& host, FileRef file, Thread thread, double& end) {
  const IoResult r = co_await host.read_file(file, 10 * MB, false, thread);
  end = sim.now();
  host.release_memory(r.bytes, thread);
}

}  // namespace

TEST_CASE("new memory goes to the toucher's node first, then to the other one, without reclaim", "[cache][numa]") {
  PageCache cache(1000, CacheSettings::kernel(), {.nodes = 2});  // two nodes of 500 bytes
  cache.set_checking(true);
  cache.touch_from(0);
  cache.add_clean(0, 300, 0.0);
  cache.allocate_anonymous(150);
  CHECK(node_use(cache, 0).cached == 300);
  CHECK(node_use(cache, 0).anonymous == 150);
  CHECK(node_use(cache, 1).cached == 0);
  // Node 0 has 50 free: the rest of a 200 file goes to node 1, nothing evicted.
  cache.add_clean(1, 200, 1.0);
  CHECK(node_use(cache, 0).free() == 0);
  CHECK(node_use(cache, 1).cached == 150);
  CHECK(cache.nodes().remote().cache == 150);
  CHECK(cache.totals().evicted == 0);
  // A thread on node 1 takes its own node's memory: nothing remote.
  cache.touch_from(1);
  cache.allocate_anonymous(100);
  CHECK(node_use(cache, 1).anonymous == 100);
  CHECK(cache.nodes().remote().anonymous == 0);
  // Released memory is its node's first: node 1's 100, then 20 of node 0's.
  cache.release_anonymous(120);
  CHECK(node_use(cache, 1).anonymous == 0);
  CHECK(node_use(cache, 0).anonymous == 130);
}

TEST_CASE("a copy into the cache takes its pages where they were reserved", "[cache][numa]") {
  PageCache cache(1000, CacheSettings::kernel(), {.nodes = 2});  // two nodes of 500 bytes
  cache.set_checking(true);
  cache.touch_from(1);
  cache.allocate_anonymous(450);
  cache.reserve(100);  // 50 on node 1, 50 on node 0
  CHECK(node_use(cache, 1).reserved == 50);
  CHECK(cache.nodes().remote().reserved == 50);
  cache.commit_dirty(0, 100, 1.0);
  CHECK(node_use(cache, 0).cached == 50);
  CHECK(node_use(cache, 1).cached == 50);
  CHECK(cache.file(0).dirty == 100);
}

TEST_CASE("each node reclaims its own data, however old the other node's is", "[cache][numa]") {
  // Node 1 full of older data, node 0 of newer: a global LRU list would take 200 from node 1;
  // each node's kswapd takes its share of its own.
  PageCache cache(1000, CacheSettings::kernel(), {.nodes = 2});  // two nodes of 500 bytes
  cache.set_checking(true);
  cache.touch_from(1);
  cache.add_clean(0, 500, 0.0);
  cache.touch_from(0);
  cache.add_clean(1, 500, 1.0);
  CHECK(cache.evict(200, cache::kNoFile) == 200);
  CHECK(cache.file(0).cached() == 400);
  CHECK(cache.file(1).cached() == 400);
  CHECK(node_use(cache, 0).free() == 100);
  CHECK(node_use(cache, 1).free() == 100);
}

TEST_CASE("a node with nothing to reclaim leaves it to the other, where the memory then is", "[cache][numa]") {
  // Node 1 full of application memory, node 0 of cache: a thread on node 1 needing 100 finds
  // them on node 0 only, reclaimed from node 0's data, and takes them there (remote).
  PageCache cache(1000, CacheSettings::kernel(), {.nodes = 2});  // two nodes of 500 bytes
  cache.set_checking(true);
  cache.touch_from(1);
  cache.allocate_anonymous(500);
  cache.touch_from(0);
  cache.add_clean(0, 500, 0.0);
  cache.touch_from(1);
  CHECK(cache.evict(100, cache::kNoFile) == 100);
  CHECK(node_use(cache, 0).free() == 100);
  cache.add_clean(1, 100, 1.0);
  CHECK(node_use(cache, 0).cached == 500);
  CHECK(cache.nodes().remote().cache == 100);
}

TEST_CASE("a node's data stays in its own blocks: a read of a file on both nodes keeps them apart", "[cache][numa]") {
  PageCache cache(1000, CacheSettings::kernel(), {.nodes = 2});  // two nodes of 500 bytes
  cache.set_checking(true);
  cache.touch_from(0);
  cache.allocate_anonymous(400);
  cache.add_clean(0, 300, 0.0);  // 100 on node 0, 200 on node 1
  cache.reaccess(0, 300, 1.0);
  CHECK(node_use(cache, 0).cached == 100);
  CHECK(node_use(cache, 1).cached == 200);
  CHECK(cache.nodes().remote().reread == 200);
}

TEST_CASE("a reader reads a file cached on the other node at the remote copy rate", "[cache][numa][host]") {
  // 100 MB cached on node 0 at the start. Read by a thread on node 0: 1000 MB/s, 0.1 s; on
  // node 1: the source is remote, 0.5 x 1000 MB/s, 0.2 s (its buffer is on its own node).
  for (const auto& [node, expected] : {std::pair{0, 0.1}, std::pair{1, 0.2}}) {
    Simulator sim;
    FairShare share(sim);
    Host host(sim, share, two_node_host(0.5));
    const FileRef file = host.add_file("in", 100 * MB, host.add_disk("d", 100e6, 100e6), true);
    double end = 0;
    sim.spawn(read_on(sim, host, file, Thread{GroupRef{}, NodeRef{static_cast<std::uint8_t>(node)}}, end));
    sim.run_until(10.0);
    INFO("reader on node " << node);
    CHECK(end == Catch::Detail::Approx(expected).epsilon(1e-9));
  }
}

TEST_CASE("a reader on node 0 reads a file a reader on node 1 cached at the remote rate", "[cache][numa][host]") {
  // A thread on node 1 reads 100 MB from a 1000 MB/s disk (0.1 s): its cache pages are node
  // 1's. At 1 s a thread on node 0 reads it again from the cache: the source is remote, 0.5 x
  // 1000 MB/s, 0.2 s; a thread on node 1 would take 0.1 s.
  for (const auto& [node, expected] : {std::pair{0, 0.2}, std::pair{1, 0.1}}) {
    Simulator sim;
    FairShare share(sim);
    Host host(sim, share, two_node_host(0.5));
    const FileRef file = host.add_file("in", 100 * MB, host.add_disk("d", 1000e6, 1000e6));
    double first = 0;
    double end = 0;
    sim.spawn(read_on(sim, host, file, Thread{GroupRef{}, NodeRef{1}}, first));
    sim.spawn([](Simulator& s, Host& h, FileRef f, int reader, double& done) -> Task<void> {
      co_await s.sleep(1.0);
      co_await read_on(s, h, f, Thread(GroupRef(), NodeRef{static_cast<std::uint8_t>(reader)}), done);
    }(sim, host, file, node, end));
    sim.run_until(10.0);
    INFO("second reader on node " << node);
    CHECK(first == Catch::Detail::Approx(0.1).epsilon(1e-9));
    CHECK(end - 1.0 == Catch::Detail::Approx(expected).epsilon(1e-9));
  }
}

TEST_CASE("a buffer on the other node pays the remote copy and first touch", "[cache][numa][host]") {
  // Node 0 (500 MB): 100 MB cached, 400 MB held. A reader on node 0 of the cached file gets its
  // buffer on node 1: the copy at 0.5 x 1000, the first touch at 0.25 x 1000 MB/s:
  // 1 / (1/500 + 1/250) = 166.7 MB/s, 0.6 s. With room on node 0: 1 / (1/1000 + 1/1000), 0.2 s.
  for (const auto& [held, expected] : {std::pair{400 * MB, 0.6}, std::pair{std::int64_t{0}, 0.2}}) {
    Simulator sim;
    FairShare share(sim);
    Host host(sim, share, two_node_host(0.5, 1000e6, 0.25));
    const FileRef file = host.add_file("in", 100 * MB, host.add_disk("d", 100e6, 100e6), true);
    double end = 0;
    sim.spawn([](Simulator& s, Host& h, FileRef f, std::int64_t bytes, double& done) -> Task<void> {
      co_await h.hold_memory(bytes, Thread());
      co_await read_on(s, h, f, Thread(), done);
    }(sim, host, file, held, end));
    sim.run_until(10.0);
    INFO("held on node 0: " << held);
    CHECK(end == Catch::Detail::Approx(expected).epsilon(1e-9));
  }
}

TEST_CASE("a node's threads reading the other node's memory reach it at the aggregate ratio", "[cache][numa][host]") {
  // Four readers on node 1 of 100 MB each cached on node 0: each alone 1000 MB/s (ratio 1);
  // together 0.25 x 2000 MB/s (their node's half of the 4000 MB/s aggregate): 500 MB/s for
  // all four, 400 MB in 0.8 s. At ratio 1: 2000 MB/s, 0.2 s.
  for (const auto& [aggregate, expected] : {std::pair{0.25, 0.8}, std::pair{1.0, 0.2}}) {
    Simulator sim;
    FairShare share(sim);
    Host host(sim, share, two_node_host(1.0, 0.0, 1.0, aggregate));
    const DiskRef disk = host.add_disk("d", 100e6, 100e6);
    double last = 0;
    std::vector<double> ends(4);
    for (int i = 0; i < 4; ++i) {
      const FileRef file = host.add_file("in" + std::to_string(i), 100 * MB, disk, true);
      sim.spawn(read_on(sim, host, file, Thread{GroupRef{}, NodeRef{1}}, ends[static_cast<std::size_t>(i)]));
    }
    sim.run_until(10.0);
    for (double e : ends) last = std::max(last, e);
    INFO("aggregate ratio " << aggregate);
    CHECK(last == Catch::Detail::Approx(expected).epsilon(1e-9));
  }
}

TEST_CASE("threads start on the node running the fewest, the lowest of equals", "[cache][numa][host]") {
  Simulator sim;
  FairShare share(sim);
  Host host(sim, share, two_node_host(0.5));
  const Thread a = host.start_thread();
  const Thread b = host.start_thread();
  const Thread c = host.start_thread();
  CHECK(a.node.index == 0);
  CHECK(b.node.index == 1);
  CHECK(c.node.index == 0);
  host.end_thread(a);
  host.end_thread(c);
  CHECK(host.start_thread().node.index == 0);
  HostSpec one = two_node_host(0.5);
  one.numa.nodes = 1;
  Host single(sim, share, one);
  CHECK(single.nodes() == 1);
  CHECK(single.start_thread().node.index == 0);
  CHECK(single.start_thread().node.index == 0);
}

TEST_CASE("[hosts.numa] is read with its keys checked", "[cache][numa][scenario]") {
  const std::string host = R"(
[pipelines]
count = 1
file_size = "1 MB"
tasks = 1
[[hosts]]
name = "n"
memory = "1 GB"
memory_read_bw = "1 GB/s"
memory_write_bw = "1 GB/s"
[[hosts.disks]]
name = "d"
read_bw = "100 MB/s"
write_bw = "100 MB/s"
[hosts.numa]
)";
  const Scenario s = parse_scenario(host + "nodes = 2\nremote_copy_ratio = 0.62\nremote_aggregate_ratio = 0.47\n", "numa.toml");
  CHECK(s.hosts[0].numa.nodes == 2);
  CHECK(s.hosts[0].numa.remote.copy == 0.62);
  CHECK(s.hosts[0].numa.remote.first_touch == 1.0);
  CHECK(s.hosts[0].numa.remote.aggregate == 0.47);
  CHECK_THROWS_WITH(parse_scenario(host + "nodes = 3\n", "numa.toml"), Catch::Contains("nodes") && Catch::Contains("between 1 and 2"));
  CHECK_THROWS_WITH(parse_scenario(host + "remote_copy_ratio = 0\n", "numa.toml"), Catch::Contains("remote_copy_ratio"));
  CHECK_THROWS_WITH(parse_scenario(host + "remote_ratio = 0.5\n", "numa.toml"), Catch::Contains("remote_ratio"));
}

namespace {

// A small reference of placement and reclaim on two nodes for clean inactive data only: each
// node's data in LRU order, as (file, bytes) runs; new memory on the toucher's node first, then
// the other; an eviction takes an equal share from each node's front, then the rest from
// whichever still has data, node 0 first.
class ReferenceNodes {
 public:
  explicit ReferenceNodes(std::int64_t per_node) { total_.fill(per_node); }
  std::int64_t free(int n) const { return total_[n] - anonymous_[n] - cached(n); }
  std::int64_t free() const { return free(0) + free(1); }
  std::int64_t cached(int n) const {
    std::int64_t sum = 0;
    for (const auto& run : lru_[n]) sum += run.second;
    return sum;
  }
  std::int64_t cached_file(std::uint32_t file) const {
    std::int64_t sum = 0;
    for (const auto& list : lru_) {
      for (const auto& run : list) sum += run.first == file ? run.second : 0;
    }
    return sum;
  }
  std::int64_t anonymous(int n) const { return anonymous_[n]; }
  void add_clean(int toucher, std::uint32_t file, std::int64_t bytes) {
    place(toucher, bytes, [&](int n, std::int64_t part) { lru_[n].push_back({file, part}); });
  }
  void allocate(int toucher, std::int64_t bytes) {
    place(toucher, bytes, [&](int n, std::int64_t part) { anonymous_[n] += part; });
  }
  void release(int toucher, std::int64_t bytes) {
    for (int i = 0; i < 2 && bytes > 0; ++i) {
      const int n = (toucher + i) % 2;
      const std::int64_t part = std::min(bytes, anonymous_[n]);
      anonymous_[n] -= part;
      bytes -= part;
    }
  }
  std::int64_t evict(std::int64_t amount) {
    std::int64_t evicted = 0;
    const std::int64_t share = (amount + 1) / 2;
    for (int n = 0; n < 2 && evicted < amount; ++n) evicted += take(n, std::min(share, amount - evicted));
    for (int n = 0; n < 2 && evicted < amount; ++n) evicted += take(n, amount - evicted);
    return evicted;
  }

 private:
  template <class Take>
  void place(int toucher, std::int64_t bytes, Take&& take_part) {
    for (int i = 0; i < 2 && bytes > 0; ++i) {
      const int n = (toucher + i) % 2;
      const std::int64_t part = std::min(bytes, free(n));
      if (part <= 0) continue;
      take_part(n, part);
      bytes -= part;
    }
  }
  std::int64_t take(int n, std::int64_t budget) {
    std::int64_t taken = 0;
    while (taken < budget && !lru_[n].empty()) {
      auto& front = lru_[n].front();
      const std::int64_t part = std::min(front.second, budget - taken);
      front.second -= part;
      taken += part;
      if (front.second == 0) lru_[n].pop_front();
    }
    return taken;
  }
  std::array<std::int64_t, 2> total_{};
  std::array<std::int64_t, 2> anonymous_{};
  std::array<std::deque<std::pair<std::uint32_t, std::int64_t>>, 2> lru_;
};

}  // namespace

TEST_CASE("placement, release and reclaim on two nodes follow a small reference, on random operations", "[cache][numa][random]") {
  for (std::uint32_t seed = 1; seed <= 40; ++seed) {
    std::mt19937 rng(seed);
    PageCache cache(1000, CacheSettings::kernel(), {.nodes = 2});  // two nodes of 500 bytes
  cache.set_checking(true);
    ReferenceNodes ref(500);
    auto pick = [&](std::int64_t low, std::int64_t high) { return std::uniform_int_distribution<std::int64_t>(low, high)(rng); };
    for (int step = 0; step < 200; ++step) {
      const int toucher = static_cast<int>(pick(0, 1));
      cache.touch_from(static_cast<cache::NodeId>(toucher));
      const std::int64_t bytes = pick(1, 120);
      const auto file = static_cast<std::uint32_t>(pick(0, 5));
      switch (pick(0, 3)) {
        case 0:
          if (bytes <= ref.free()) cache.add_clean(file, bytes, step), ref.add_clean(toucher, file, bytes);
          break;
        case 1:
          if (bytes <= ref.free()) cache.allocate_anonymous(bytes), ref.allocate(toucher, bytes);
          break;
        case 2: {
          const std::int64_t held = cache.memory().anonymous;
          cache.release_anonymous(std::min(bytes, held));
          ref.release(toucher, std::min(bytes, held));
          break;
        }
        default:
          CHECK(cache.evict(bytes, cache::kNoFile) == ref.evict(bytes));
      }
      INFO("seed " << seed << ", step " << step);
      for (int n = 0; n < 2; ++n) {
        const NodeUse use = node_use(cache, static_cast<cache::NodeId>(n));
        REQUIRE(use.cached == ref.cached(n));
        REQUIRE(use.anonymous == ref.anonymous(n));
      }
      for (std::uint32_t f = 0; f <= 5; ++f) REQUIRE(cache.file(f).cached() == ref.cached_file(f));
    }
  }
}

TEST_CASE("every policy keeps a two-node host's nodes; the host model's numa_nodes and the paper profile make it one",
          "[numa][policy]") {
  const std::string file = std::string(PCSIM_SOURCE_DIR) + "/scenarios/examples/two-sockets.toml";
  auto nodes_of = [&](const std::vector<std::pair<std::string, std::string>>& overrides, const std::string& profile = "") {
    const Scenario s = load_scenario(file, overrides, profile);
    const HostConfig& c = s.hosts.at(0);
    Simulator sim;
    FairShare share(sim);
    const Host host(sim, share,
                    HostSpec{c.name, c.cores, c.memory, c.memory_bandwidth, c.cache, c.memory_in_use, c.page_reporting_delay,
                             c.memory_freed_at_start, c.request_time, c.numa});
    return host.nodes();
  };
  for (const char* policy : {"kernel", "lru", "arc"}) {
    INFO(policy);
    CHECK(nodes_of({{"hosts.0.page_cache.policy", fmt::format("\"{}\"", policy)}}) == 2);
    CHECK(nodes_of({{"hosts.0.page_cache.policy", fmt::format("\"{}\"", policy)}, {"hosts.0.page_cache.numa_nodes", "false"}}) == 1);
  }
  CHECK(nodes_of({}, "paper") == 1);
  CHECK(nodes_of({{"hosts.0.page_cache.numa_nodes", "true"}}, "paper") == 2);
}
