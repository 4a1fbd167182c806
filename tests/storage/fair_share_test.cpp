// Analytic tests of the fair-share model: each expected time is derived in a comment from
// the max-min definition (fair_share.hpp), then checked.
#include "support/flow_runner.hpp"

#include <pagecache/devices.hpp>
#include <pagecache/error.hpp>
#include <pagecache/fair_share.hpp>

#include <catch2/catch.hpp>

#include <array>
#include <vector>

using namespace pagecache;
using pagecache::testing::bytes_through;
using pagecache::testing::flow_at;

namespace {
constexpr double MB = 1e6;
constexpr double GB = 1e9;

Task<void> read_at(Simulator& sim, const Disk& disk, double start, double bytes, double& finished) {
  co_await sim.sleep_until(start);
  co_await disk.read(static_cast<std::int64_t>(bytes));
  finished = sim.now();
}
Task<void> write_at(Simulator& sim, const Disk& disk, double start, double bytes, double& finished) {
  co_await sim.sleep_until(start);
  co_await disk.write(static_cast<std::int64_t>(bytes));
  finished = sim.now();
}
}  // namespace

TEST_CASE("four equal reads on a 100 MB/s disk each finish at 4 s", "[fair_share]") {
  // Each gets 1/4 of the disk: 25 MB/s, so 100 MB takes 4 s.
  Simulator sim;
  FairShare share(sim);
  Disk disk(share, "disk", 100 * MB, 100 * MB);
  std::array<double, 4> done{};
  for (auto& d : done) sim.spawn(read_at(sim, disk, 0.0, 100 * MB, d));
  sim.run_until(1.0);
  CHECK(share.active_flows(disk.resource()) == 4);
  CHECK(share.utilization(disk.resource()) == Catch::Detail::Approx(1.0));
  share.check_invariants();
  sim.run();
  for (double d : done) CHECK(d == Catch::Detail::Approx(4.0).epsilon(1e-12));
  CHECK(share.active_flows() == 0);
}

TEST_CASE("streams on a disk whose aggregate is above one stream's: each capped, together up to the aggregate", "[fair_share][disk_streams]") {
  // One stream at most 100 MB/s, all streams together 250 MB/s (reads). One read of 100 MB:
  // 1 s (its stream's cap, not the disk's 0.4 s). Two reads: 100 MB/s each (both capped,
  // 200 < 250): 1 s. Three reads: 250 / 3 MB/s each, the disk saturated: 300 MB in 1.2 s.
  // A write, streams 50 and aggregate 100 MB/s, beside a read: the read at r, the write at w
  // with w <= 50, r <= 100 and r / 250 + w / 100 <= 1: max-min raises both to 50 together
  // (50/250 + 50/100 = 0.7), then the read alone to its cap 100 (0.4 + 0.5 = 0.9): 100 MB of
  // each: the read done at 1 s, the write then alone at 50 MB/s: 100 MB at 2 s.
  for (const int n : {1, 2, 3}) {
    Simulator sim;
    FairShare share(sim);
    const Disk disk(share, "disk", DiskBandwidth{.read = 100 * MB, .write = 50 * MB, .aggregate_read = 250 * MB, .aggregate_write = 100 * MB});
    std::vector<double> done(static_cast<std::size_t>(n));
    for (auto& d : done) sim.spawn(read_at(sim, disk, 0.0, 100 * MB, d));
    sim.run();
    INFO(n << " streams");
    for (double d : done) CHECK(d == Catch::Detail::Approx(n == 3 ? 1.2 : 1.0).epsilon(1e-12));
  }
  Simulator sim;
  FairShare share(sim);
  const Disk disk(share, "disk", DiskBandwidth{.read = 100 * MB, .write = 50 * MB, .aggregate_read = 250 * MB, .aggregate_write = 100 * MB});
  double read_done = 0, write_done = 0;
  sim.spawn(read_at(sim, disk, 0.0, 100 * MB, read_done));
  sim.spawn(write_at(sim, disk, 0.0, 100 * MB, write_done));
  sim.run();
  CHECK(read_done == Catch::Detail::Approx(1.0).epsilon(1e-12));
  CHECK(write_done == Catch::Detail::Approx(2.0).epsilon(1e-12));
  // Equal rates (the default) are one stream taking the whole disk: two reads share 100 MB/s.
  Simulator sim2;
  FairShare share2(sim2);
  const Disk plain(share2, "disk", 100 * MB, 100 * MB);
  std::array<double, 2> both{};
  for (auto& d : both) sim2.spawn(read_at(sim2, plain, 0.0, 100 * MB, d));
  sim2.run();
  for (double d : both) CHECK(d == Catch::Detail::Approx(2.0).epsilon(1e-12));
  CHECK_THROWS_WITH(Disk(share2, "slow", DiskBandwidth{.read = 100 * MB, .write = 100 * MB, .aggregate_read = 50 * MB}),
                    Catch::Contains("aggregate bandwidth is below one stream's"));
}

TEST_CASE("a read and a write on a disk with read 200 and write 100 MB/s get the same rate", "[fair_share]") {
  // Equal rates r with r/200 + r/100 = 1 -> r = 200/3 MB/s. The 100 MB read ends at
  // 100 / (200/3) = 1.5 s, when the write has 100 MB left of 200; alone at 100 MB/s it needs
  // 1 s more: 2.5 s.
  Simulator sim;
  FairShare share(sim);
  Disk disk(share, "disk", 200 * MB, 100 * MB);
  double read_done = 0;
  double write_done = 0;
  sim.spawn(read_at(sim, disk, 0.0, 100 * MB, read_done));
  sim.spawn(write_at(sim, disk, 0.0, 200 * MB, write_done));
  sim.run();
  CHECK(read_done == Catch::Detail::Approx(1.5).epsilon(1e-12));
  CHECK(write_done == Catch::Detail::Approx(2.5).epsilon(1e-12));
}

TEST_CASE("a flow arriving later shares the disk from its arrival on", "[fair_share]") {
  // Disk 100 MB/s. A (100 MB) alone from 0 to 0.5 s: 50 MB done. Then A and B (100 MB) at
  // 50 MB/s each: A's last 50 MB take 1 s, A ends at 1.5 s, B has 50 MB left; alone it
  // needs 0.5 s: B ends at 2.0 s (the disk moved 200 MB in 2 s).
  Simulator sim;
  FairShare share(sim);
  Disk disk(share, "disk", 100 * MB, 100 * MB);
  double a = 0;
  double b = 0;
  sim.spawn(read_at(sim, disk, 0.0, 100 * MB, a));
  sim.spawn(read_at(sim, disk, 0.5, 100 * MB, b));
  sim.run();
  CHECK(a == Catch::Detail::Approx(1.5).epsilon(1e-12));
  CHECK(b == Catch::Detail::Approx(2.0).epsilon(1e-12));
}

TEST_CASE("a flow crossing a disk and a link runs at the slower one's share", "[fair_share]") {
  // Disk 100 MB/s, link 30 MB/s (no latency). Remote read R (60 MB) crosses both; local read
  // L (70 MB) the disk only. Progressive filling: both grow together; the link saturates
  // first at 30 MB/s (R frozen at 30); the disk has 1 - 30/100 = 0.7 left, so L gets 70 MB/s.
  // L ends at 70/70 = 1 s; R, still capped by the link, ends at 60/30 = 2 s.
  Simulator sim;
  FairShare share(sim);
  Disk disk(share, "disk", 100 * MB, 100 * MB);
  Link link(share, "link", 30 * MB, 0.0);
  double remote = 0;
  double local = 0;
  auto remote_read = [](Simulator& s, const Disk& d, const Link& l, double& done) -> Task<void> {
    co_await l.send_through(FlowSpec{.work = 60 * MB}.through(d.read_usage()));
    done = s.now();
  };
  sim.spawn(remote_read(sim, disk, link, remote));
  sim.spawn(read_at(sim, disk, 0.0, 70 * MB, local));
  sim.run_until(0.5);
  CHECK(share.utilization(disk.resource()) == Catch::Detail::Approx(1.0));
  CHECK(share.utilization(link.resource()) == Catch::Detail::Approx(1.0));
  share.check_invariants();
  sim.run();
  CHECK(local == Catch::Detail::Approx(1.0).epsilon(1e-12));
  CHECK(remote == Catch::Detail::Approx(2.0).epsilon(1e-12));
}

TEST_CASE("a link's latency is paid once before the transfer", "[fair_share]") {
  // 0.5 s latency, then 100 MB at 100 MB/s: 1.5 s.
  Simulator sim;
  FairShare share(sim);
  Link link(share, "link", 100 * MB, 0.5);
  double done = 0;
  auto send = [](Simulator& s, const Link& l, double& d) -> Task<void> {
    co_await l.send(static_cast<std::int64_t>(100 * MB));
    d = s.now();
  };
  sim.spawn(send(sim, link, done));
  sim.run();
  CHECK(done == Catch::Detail::Approx(1.5).epsilon(1e-12));
}

TEST_CASE("memory copies run at the per-flow bound until the aggregate saturates", "[fair_share]") {
  // Per-flow read 10 GB/s, aggregate read 25 GB/s. Two 10 GB reads: 2 x 10 <= 25, each at its
  // bound: 1 s. Four 10 GB reads: 4 x 10 > 25, so each gets 25/4 = 6.25 GB/s: 1.6 s.
  for (const auto& [flows, expected] : {std::pair{2, 1.0}, std::pair{4, 1.6}}) {
    Simulator sim;
    FairShare share(sim);
    Memory memory(share, "memory", MemoryBandwidth{10 * GB, 5 * GB, 25 * GB, 20 * GB});
    std::vector<double> done(static_cast<std::size_t>(flows));
    auto copy = [](Simulator& s, const Memory& m, double& d) -> Task<void> {
      co_await m.read(static_cast<std::int64_t>(10 * GB));
      d = s.now();
    };
    for (auto& d : done) sim.spawn(copy(sim, memory, d));
    sim.run();
    for (double d : done) CHECK(d == Catch::Detail::Approx(expected).epsilon(1e-12));
  }
}

TEST_CASE("memory reads and writes share the aggregate in proportion to its cost", "[fair_share]") {
  // Per-flow 10 GB/s read, 5 GB/s write; aggregate 12 GB/s read, 6 GB/s write. One reader and
  // one writer: at their bounds they would use 10/12 + 5/6 > 1, so they share at one rate r
  // (neither bound is reached below it): r/12 + r/6 = 1 -> r = 4 GB/s. 8 GB each: 2 s.
  Simulator sim;
  FairShare share(sim);
  Memory memory(share, "memory", MemoryBandwidth{10 * GB, 5 * GB, 12 * GB, 6 * GB});
  double read_done = 0;
  double write_done = 0;
  sim.spawn(flow_at(sim, share, 0.0, memory.read_spec(static_cast<std::int64_t>(8 * GB)), read_done));
  sim.spawn(flow_at(sim, share, 0.0, memory.write_spec(static_cast<std::int64_t>(8 * GB)), write_done));
  sim.run();
  CHECK(read_done == Catch::Detail::Approx(2.0).epsilon(1e-12));
  CHECK(write_done == Catch::Detail::Approx(2.0).epsilon(1e-12));
}

TEST_CASE("a bounded flow keeps its bound and the others share what is left", "[fair_share]") {
  // Disk 100 MB/s. A is bounded at 20 MB/s; B and C are not. A gets 20; B and C share 80:
  // 40 each. A (20 MB) ends at 1 s; B and C (80 MB) have 40 MB left and now get 50 MB/s:
  // 0.8 s more, 1.8 s.
  Simulator sim;
  FairShare share(sim);
  const ResourceId disk = share.add_resource("disk");
  const Usage use{disk, 1.0 / (100 * MB)};
  double a = 0, b = 0, c = 0;
  sim.spawn(flow_at(sim, share, 0.0, bytes_through(20 * MB, use).with_bound(20 * MB), a));
  sim.spawn(flow_at(sim, share, 0.0, bytes_through(80 * MB, use), b));
  sim.spawn(flow_at(sim, share, 0.0, bytes_through(80 * MB, use), c));
  sim.run_until(0.5);
  share.check_invariants();
  sim.run();
  CHECK(a == Catch::Detail::Approx(1.0).epsilon(1e-12));
  CHECK(b == Catch::Detail::Approx(1.8).epsilon(1e-12));
  CHECK(c == Catch::Detail::Approx(1.8).epsilon(1e-12));
}

TEST_CASE("weights split a saturated resource in proportion", "[fair_share]") {
  // 90 MB/s; weights 2 and 1 -> 60 and 30 MB/s. 60 MB each: the heavy one ends at 1 s, the
  // light one has 30 MB left and the whole disk: 30/90 s more, 4/3 s.
  Simulator sim;
  FairShare share(sim);
  const ResourceId disk = share.add_resource("disk");
  const Usage use{disk, 1.0 / (90 * MB)};
  double heavy = 0, light = 0;
  sim.spawn(flow_at(sim, share, 0.0, bytes_through(60 * MB, use).with_weight(2.0), heavy));
  sim.spawn(flow_at(sim, share, 0.0, bytes_through(60 * MB, use), light));
  sim.run();
  CHECK(heavy == Catch::Detail::Approx(1.0).epsilon(1e-12));
  CHECK(light == Catch::Detail::Approx(4.0 / 3.0).epsilon(1e-12));
}

TEST_CASE("a CPU with more tasks than cores gives each min(1, cores/tasks) of a core", "[fair_share]") {
  // 4 cores, 6 tasks: 2 of 1 s and 4 of 3 s. Each runs at 4/6 of a core; the short ones end
  // at 1 / (2/3) = 1.5 s, when the long ones have 2 s left; 4 tasks on 4 cores run at full
  // speed: they end at 3.5 s.
  Simulator sim;
  FairShare share(sim);
  Cpu cpu(share, "cpu", 4);
  std::vector<double> done(6);
  auto task = [](Simulator& s, const Cpu& c, double seconds, double& d) -> Task<void> {
    co_await c.compute(seconds);
    d = s.now();
  };
  for (std::size_t i = 0; i < 6; ++i) sim.spawn(task(sim, cpu, i < 2 ? 1.0 : 3.0, done[i]));
  sim.run();
  for (std::size_t i = 0; i < 6; ++i) CHECK(done[i] == Catch::Detail::Approx(i < 2 ? 1.5 : 3.5).epsilon(1e-12));
}

TEST_CASE("fewer tasks than cores each run at one core", "[fair_share]") {
  Simulator sim;
  FairShare share(sim);
  Cpu cpu(share, "cpu", 32);
  double done = 0;
  auto task = [](Simulator& s, const Cpu& c, double& d) -> Task<void> {
    co_await c.compute(28.0);
    d = s.now();
  };
  sim.spawn(task(sim, cpu, done));
  sim.run();
  CHECK(done == Catch::Detail::Approx(28.0).epsilon(1e-12));
}

TEST_CASE("a zero-byte flow completes without waiting", "[fair_share]") {
  Simulator sim;
  FairShare share(sim);
  Disk disk(share, "disk", 100 * MB, 100 * MB);
  double done = -1;
  sim.spawn(read_at(sim, disk, 1.0, 0.0, done));
  sim.run();
  CHECK(done == 1.0);
}

TEST_CASE("invalid flows and devices are rejected with a message", "[fair_share]") {
  Simulator sim;
  FairShare share(sim);
  const ResourceId disk = share.add_resource("disk");
  CHECK_THROWS_AS(Disk(share, "bad", -1.0, 1.0), ConfigError);
  CHECK_THROWS_AS(Cpu(share, "cpu", 0), ConfigError);
  auto start = [](FairShare& s, FlowSpec spec) -> Task<void> { co_await s.transfer(spec); };
  sim.spawn(start(share, FlowSpec{.work = 1.0}));
  CHECK_THROWS_WITH(sim.run(), Catch::Contains("crosses no resource"));
  sim.spawn(start(share, FlowSpec{.work = -1.0}.through({disk, 1.0})));
  CHECK_THROWS_WITH(sim.run(), Catch::Contains("work"));
  sim.spawn(start(share, FlowSpec{.work = 1.0}.through({disk, 0.0})));
  CHECK_THROWS_WITH(sim.run(), Catch::Contains("cost"));
  sim.spawn(start(share, FlowSpec{.work = 1.0}.through({disk, 1.0}).through({disk, 1.0})));
  CHECK_THROWS_WITH(sim.run(), Catch::Contains("twice"));
  CHECK(share.active_flows() == 0);
}

TEST_CASE("tearing down a simulation with flows in progress is clean", "[fair_share]") {
  // Flows withdrawn by their processes' destruction, in either destruction order.
  {
    Simulator sim;
    FairShare share(sim);
    Disk disk(share, "disk", 100 * MB, 100 * MB);
    double done = 0;
    sim.spawn(read_at(sim, disk, 0.0, 100 * MB, done));
    sim.spawn(read_at(sim, disk, 0.0, 100 * MB, done));
    sim.run_until(0.5);
  }
  {
    auto sim = std::make_unique<Simulator>();
    auto share = std::make_unique<FairShare>(*sim);
    Disk disk(*share, "disk", 100 * MB, 100 * MB);
    Link link(*share, "link", 10 * MB, 0.0);
    double done = 0;
    auto remote = [](const Disk& d, const Link& l) -> Task<void> {
      co_await l.send_through(FlowSpec{.work = 60 * MB}.through(d.read_usage()));
    };
    sim->spawn(remote(disk, link));
    sim->spawn(read_at(*sim, disk, 0.0, 100 * MB, done));
    sim->run_until(0.5);
    share.reset();  // the FairShare goes first: its flows are detached
    sim.reset();
  }
  {
    // The processes go first: each coupled flow withdrawn leaves its class, the others are
    // solved again.
    auto sim = std::make_unique<Simulator>();
    FairShare share(*sim);
    Disk disk(share, "disk", 100 * MB, 100 * MB);
    Link link(share, "link", 10 * MB, 0.0);
    auto remote = [](const Disk& d, const Link& l, double bytes) -> Task<void> {
      co_await l.send_through(FlowSpec{.work = bytes}.through(d.read_usage()));
    };
    for (double bytes : {60 * MB, 60 * MB, 30 * MB}) sim->spawn(remote(disk, link, bytes));
    double done = 0;
    sim->spawn(read_at(*sim, disk, 0.0, 100 * MB, done));
    sim->run_until(0.5);
    CHECK(share.active_flows() == 4);
    share.check_invariants();
    sim.reset();
    CHECK(share.active_flows() == 0);
    share.check_invariants();
  }
  SUCCEED();
}

TEST_CASE("a flow crossing eight resources is solved with all eight", "[fair_share]") {
  // A route of six links plus two ends: flow A crosses resources 0..7 (100 MB/s each, the
  // first 50 MB/s); B crosses resources 0 and 1. Resource 0 bottlenecks both: 25 MB/s each, so
  // B's 25 MB end at 1 s, after which A has it alone: A's last 25 MB at 50 MB/s, 1.5 s in all.
  // (The solver once kept four resources per flow: the others overwrote the first costs.)
  Simulator sim;
  FairShare share(sim);
  std::vector<ResourceId> r;
  for (int i = 0; i < 8; ++i) r.push_back(share.add_resource("r" + std::to_string(i)));
  FlowSpec a{.work = 50 * MB};
  for (int i = 0; i < 8; ++i) a.through({r[static_cast<std::size_t>(i)], 1.0 / ((i == 0 ? 50 : 100) * MB)});
  FlowSpec b{.work = 25 * MB};
  b.through({r[0], 1.0 / (50 * MB)}).through({r[1], 1.0 / (100 * MB)});
  double a_done = 0;
  double b_done = 0;
  sim.spawn(flow_at(sim, share, 0.0, a, a_done));
  sim.spawn(flow_at(sim, share, 0.0, b, b_done));
  sim.run();
  CHECK(b_done == Catch::Detail::Approx(1.0));
  CHECK(a_done == Catch::Detail::Approx(1.5));
}
