// Memory groups on a host (cgroup v2 memory.max, first cut): a group reclaims its own data at
// its limit while the host has free memory, writes back its own dirty data, and fails with
// the time and the group when nothing can free enough. Expected values derived in comments.
#include <pagecache/host.hpp>

#include <pagecache/error.hpp>
#include <pagecache/simulator.hpp>

#include <catch2/catch.hpp>

using namespace pagecache;

namespace {

constexpr std::int64_t MB = 1'000'000;

// 10 GB of memory, 4 cores; disk 100 MB/s; memory copies 1000 MB/s.
HostSpec host_spec() {
  return HostSpec{.name = "h",
                  .cores = 4,
                  .memory = 10'000 * MB,
                  .memory_bandwidth = MemoryBandwidth::shared_channel(1000e6),
                  .cache = CacheSettings::kernel()};
}

}  // namespace

TEST_CASE("a reader in a memory group reclaims its own cached data at the limit while the host has free memory", "[host][groups]") {
  // A 1 GB file read in 100 MB chunks by a task in a group of 1.5 GB: each chunk charges 100
  // MB of buffer and 100 MB of new cache data. After 7 chunks the group holds 1.4 GB; the 8th
  // needs 200 MB with 100 MB left, so 100 MB of the group's oldest data (the file's first
  // chunk) goes; the 9th and 10th evict 200 MB each. At the end: buffers 1 GB, cached 500
  // MB, usage 1.5 GB, with 8.5 GB of the host free. Without a group: all 1 GB stays cached.
  for (const bool grouped : {true, false}) {
    Simulator sim;
    FairShare share(sim);
    Host host(sim, share, host_spec());
    host.set_checking(true);
    const FileRef file = host.add_file("in", 1000 * MB, host.add_disk("d", 100e6, 100e6));
    const GroupRef group = grouped ? host.add_memory_group(1500 * MB) : GroupRef{};
    std::int64_t usage = 0, cached = 0, free = 0;
    auto read = [](Host& h, FileRef f, GroupRef g, std::int64_t& u, std::int64_t& c, std::int64_t& fr) -> Task<void> {
      const IoResult r = co_await h.read_file(f, 100 * MB, false, g);
      u = h.group_usage(g);
      c = h.cached(f);
      fr = h.memory().free;
      h.release_memory(r.bytes, g);
    };
    sim.spawn(read(host, file, group, usage, cached, free));
    sim.run();
    INFO("grouped " << grouped);
    CHECK(cached == (grouped ? 500 * MB : 1000 * MB));
    if (grouped) {
      CHECK(usage == 1500 * MB);
      CHECK(free == 8500 * MB);
      CHECK(host.group_usage(group) == 500 * MB);  // its buffers released
    }
  }
}

TEST_CASE("a writer in a memory group writes back its own dirty data to stay under its limit", "[host][groups]") {
  // 2 GB written into the cache by a task in a group of 600 MB, on a host whose dirty limits
  // (20 % of 10 GB) the group never reaches: only the group's limits make it write back (its
  // memory.max, and its own dirty limits, whose background writeback does most of it). The
  // group's cache never exceeds 600 MB, so at the end the file has at most 600 MB cached and
  // at least 1.4 GB went to the disk before the write ended (the periodic flusher's 30 s
  // expiry is not reached: 2 GB at 100 MB/s is 20 s of writeback at most).
  Simulator sim;
  FairShare share(sim);
  Host host(sim, share, host_spec());
  host.set_checking(true);
  const FileRef file = host.add_file("out", 2000 * MB, host.add_disk("d", 100e6, 100e6));
  const GroupRef group = host.add_memory_group(600 * MB);
  std::int64_t peak = 0;
  host.set_memory_observer([&](double, const MemoryState&) { peak = std::max(peak, host.group_usage(group)); });
  double written = 0;
  auto write = [](Simulator& s, Host& h, FileRef f, GroupRef g, double& done) -> Task<void> {
    co_await h.write_file(f, 100 * MB, false, g);
    done = s.now();
  };
  sim.spawn(write(sim, host, file, group, written));
  sim.run_until(60.0);
  CHECK(written > 0.0);
  CHECK(peak <= 600 * MB);
  CHECK(host.cached(file) <= 600 * MB);
  CHECK(host.forced_flush_bytes() + host.periodic_flush_bytes() >= 1400 * MB);
  CHECK(host.memory().free >= 9400 * MB);
}

TEST_CASE("a group that cannot free enough fails with the time and the group", "[host][groups]") {
  // A task of a 150 MB group asks for 200 MB of memory: nothing of the group is cached, so
  // nothing can be freed: out of memory in the group, at t = 0, though the host has 10 GB free.
  Simulator sim;
  FairShare share(sim);
  Host host(sim, share, host_spec());
  const GroupRef group = host.add_memory_group(150 * MB);
  auto hold = [](Host& h, GroupRef g) -> Task<void> { co_await h.hold_memory(200 * MB, g); };
  sim.spawn(hold(host, group));
  CHECK_THROWS_WITH(sim.run(), Catch::Contains("t = 0.000000 s") && Catch::Contains("memory group 1 is at its limit") &&
                                   Catch::Contains("memory.max 150000000 bytes"));
  CHECK_THROWS_AS(host.group_usage(GroupRef{7}), ConfigError);
}

TEST_CASE("above memory.high a group reclaims its own data but is never refused", "[host][groups]") {
  // The reader of the first case, in a group of memory.max 1.5 GB and memory.high 1 GB: each
  // chunk whose charge (100 MB of buffer, 100 MB of new cache) would take the group above
  // 1 GB first evicts the group's cache. Before the last chunk the group holds 900 MB of
  // buffers and the previous chunk's 100 MB of cache: that 100 MB goes, and the last chunk
  // leaves 1 GB of buffers and its own 100 MB cached (pcsim reclaims before a charge, the
  // kernel right after it, on the way back to user space: one chunk apart). Never refused:
  // the limit is not reached. memory.high above memory.max is refused.
  Simulator sim;
  FairShare share(sim);
  Host host(sim, share, host_spec());
  host.set_checking(true);
  const FileRef file = host.add_file("in", 1000 * MB, host.add_disk("d", 100e6, 100e6));
  const GroupRef group = host.add_memory_group(1500 * MB, 1000 * MB);
  std::int64_t usage = 0, cached = -1;
  auto read = [](Host& h, FileRef f, GroupRef g, std::int64_t& u, std::int64_t& c) -> Task<void> {
    const IoResult r = co_await h.read_file(f, 100 * MB, false, g);
    u = h.group_usage(g);
    c = h.cached(f);
    h.release_memory(r.bytes, g);
  };
  sim.spawn(read(host, file, group, usage, cached));
  sim.run();
  CHECK(cached == 100 * MB);
  CHECK(usage == 1100 * MB);
  CHECK_THROWS_AS(host.add_memory_group(100 * MB, 200 * MB), ConfigError);
}

TEST_CASE("a group's dirty data is throttled at its own dirty limit while the host's is far away", "[host][groups]") {
  // 1.5 GB written in 100 MB chunks by a task of a 1 GB group on the 10 GB host. The group's
  // writeback domain (mdtc_calculate_avail): its cached data plus its headroom, since the
  // host's clean memory outside the group exceeds that headroom: 1 GB throughout. Its
  // thresholds are 20 % and 10 % of that: thresh 200 MB, background 100 MB, freerun 150 MB,
  // setpoint 175 MB. The host's (of ~10 GB dirtyable: thresh 2 GB, freerun 1.5 GB, setpoint
  // 1.75 GB) are never approached.
  // A chunk goes free while the group has <= 100 MB dirty or in writeback, so the group
  // holds at most 200 MB; over 100 MB its background writeback starts; at 200 MB its
  // position ratio is 0 and the writer waits for that writeback. Writing is paced by the
  // 100 MB/s disk: at the end at most 200 MB is not yet written back, so at least 1.3 GB
  // left by the flusher, and the write took at least 13 s. Without the group's own limits
  // (the root group) the host's free run lets the whole 1.5 GB into the cache, dirty or in
  // writeback, in 1.5 s at the 1000 MB/s of memory copies.
  for (const bool grouped : {true, false}) {
    Simulator sim;
    FairShare share(sim);
    Host host(sim, share, host_spec());
    host.set_checking(true);
    const FileRef file = host.add_file("out", 1500 * MB, host.add_disk("d", 100e6, 100e6));
    const GroupRef group = grouped ? host.add_memory_group(1000 * MB) : GroupRef{};
    std::int64_t peak = 0;
    host.set_memory_observer([&](double, const MemoryState& m) { peak = std::max(peak, m.dirty + m.writeback); });
    double written = 0;
    std::int64_t unwritten = 0;
    auto write = [](Simulator& s, Host& h, FileRef f, GroupRef g, double& done, std::int64_t& left) -> Task<void> {
      co_await h.write_file(f, 100 * MB, false, g);
      done = s.now();
      left = h.memory().dirty + h.memory().writeback;
    };
    sim.spawn(write(sim, host, file, group, written, unwritten));
    sim.run_until(60.0);
    INFO("grouped " << grouped);
    REQUIRE(written > 0.0);
    if (grouped) {
      CHECK(peak == 200 * MB);
      CHECK(unwritten <= 200 * MB);
      CHECK(written >= 13.0);
    } else {
      CHECK(peak == 1500 * MB);
      CHECK(written == Approx(1.5));
    }
  }
}
