// A disk's write cache: writes fill it at the burst rate while the medium drains it at the
// sustained rate (a fluid model, planned as each write starts). Each expected time derived in
// a comment, then checked.
#include <pagecache/devices.hpp>
#include <pagecache/error.hpp>

#include <catch2/catch.hpp>

#include <cstdint>

using namespace pagecache;

namespace {

constexpr double GB = 1e9;
constexpr double MB = 1e6;

Task<void> write_at(Simulator& sim, const Disk& disk, double start, std::int64_t bytes, double& finished) {
  co_await sim.sleep_until(start);
  co_await disk.write(bytes);
  finished = sim.now();
}

Task<void> read_at(Simulator& sim, const Disk& disk, double start, std::int64_t bytes, double& finished) {
  co_await sim.sleep_until(start);
  co_await disk.read(bytes);
  finished = sim.now();
}

// 1 GB/s reading and writing into a 1 GB write cache, whose medium takes 250 MB/s.
DiskBandwidth cached_ssd() { return {.read = 1 * GB, .write = 1 * GB, .write_cache = 1'000'000'000, .sustained_write = 250 * MB}; }

// When `disk` finishes a write of `bytes` starting at `start` (the simulation run to its end).
double write_time(Simulator& sim, const Disk& disk, double start, std::int64_t bytes) {
  double done = -1.0;
  sim.spawn(write_at(sim, disk, start, bytes, done));
  sim.run();
  return done;
}

}  // namespace

TEST_CASE("a burst that fits the write cache goes at the burst rate", "[devices][write_cache]") {
  // 500 MB at 1 GB/s: 0.5 s, while the medium drains 250 MB/s x 0.5 s = 125 MB of it: 375 MB
  // left in the cache.
  Simulator sim;
  FairShare share(sim);
  const Disk disk(share, "ssd", cached_ssd());
  CHECK(write_time(sim, disk, 0.0, 500'000'000) == Approx(0.5).epsilon(1e-12));
  CHECK(disk.write_cache_fill() == Approx(375 * MB).epsilon(1e-12));
  CHECK(disk.write_cache() == 1'000'000'000);
  CHECK(disk.sustained_write_bandwidth() == 250 * MB);
}

TEST_CASE("a write twice as large as the write cache bursts until the cache is full, then goes at the medium's rate", "[devices][write_cache]") {
  // 2 GB into an empty 1 GB cache. The cache fills at 1 GB/s - 250 MB/s = 750 MB/s: full after
  // 1 GB / 750 MB/s = 4/3 s, the write having put 4/3 GB in it at 1 GB/s. The other 2/3 GB go at
  // 250 MB/s: 8/3 s. In all 4 s, the cache full at the end.
  Simulator sim;
  FairShare share(sim);
  const Disk disk(share, "ssd", cached_ssd());
  CHECK(write_time(sim, disk, 0.0, 2'000'000'000) == Approx(4.0).epsilon(1e-12));
  CHECK(disk.write_cache_fill() == Approx(1 * GB).epsilon(1e-12));
}

TEST_CASE("after a pause the medium has drained the write cache, which takes a burst again", "[devices][write_cache]") {
  // Full at 4 s (above). 4 s later the medium has drained 250 MB/s x 4 s = 1 GB: empty, and
  // 500 MB go at 1 GB/s: 0.5 s, from 8 s to 8.5 s.
  Simulator sim;
  FairShare share(sim);
  const Disk disk(share, "ssd", cached_ssd());
  REQUIRE(write_time(sim, disk, 0.0, 2'000'000'000) == Approx(4.0).epsilon(1e-12));
  CHECK(write_time(sim, disk, 8.0, 500'000'000) == Approx(8.5).epsilon(1e-12));
  // Half drained: full at 4 s, 2 s of pause drain 500 MB. A 1 GB write then fills the 500 MB of
  // room at 750 MB/s in 2/3 s, putting 2/3 GB in at 1 GB/s; the last 1/3 GB at 250 MB/s take
  // 4/3 s: 2 s, from 6 s to 8 s.
  Simulator sim2;
  FairShare share2(sim2);
  const Disk half(share2, "ssd", cached_ssd());
  REQUIRE(write_time(sim2, half, 0.0, 2'000'000'000) == Approx(4.0).epsilon(1e-12));
  CHECK(write_time(sim2, half, 6.0, 1'000'000'000) == Approx(8.0).epsilon(1e-12));
}

TEST_CASE("a write past the write cache loads the disk as its medium would", "[devices][write_cache]") {
  // The cache full, a 250 MB write goes at 250 MB/s and takes 1 / 250 MB of the disk per byte,
  // as on a disk writing at 250 MB/s. A 200 MB read beside it: both at r with
  // r / 1 GB/s + r / 250 MB/s = 1, r = 200 MB/s; the read done at 1 s, the write's last 50 MB
  // then alone at 250 MB/s: 0.2 s more. The same on a 1 GB/s / 250 MB/s disk without cache.
  for (const bool cached : {true, false}) {
    Simulator sim;
    FairShare share(sim);
    const Disk disk = cached ? Disk(share, "ssd", cached_ssd()) : Disk(share, "hdd", 1 * GB, 250 * MB);
    const double start = cached ? write_time(sim, disk, 0.0, 2'000'000'000) : 0.0;
    double read_done = 0.0, write_done = 0.0;
    sim.spawn(read_at(sim, disk, start, 200'000'000, read_done));
    sim.spawn(write_at(sim, disk, start, 250'000'000, write_done));
    sim.run();
    INFO((cached ? "full write cache" : "no write cache"));
    CHECK(read_done - start == Approx(1.0).epsilon(1e-12));
    CHECK(write_done - start == Approx(1.2).epsilon(1e-12));
  }
}

TEST_CASE("a disk without a write cache writes as before", "[devices][write_cache]") {
  // write_cache 0: the same bound and share of the disk as a disk made without the field, and
  // the same times, to the bit, streams slower than the disk included.
  for (const double aggregate : {0.0, 800 * MB}) {
    Simulator sim_before, sim_now;
    FairShare share_before(sim_before), share_now(sim_now);
    const Disk before(share_before, "a", DiskBandwidth{.read = 500 * MB, .write = 400 * MB, .aggregate_write = aggregate});
    const Disk now(share_now, "a", DiskBandwidth{.read = 500 * MB, .write = 400 * MB, .aggregate_write = aggregate, .write_cache = 0,
                                                 .sustained_write = 0.0});
    FlowSpec x{.work = 1e9}, y{.work = 1e9};
    before.writing(x);
    now.writing(y);
    CHECK(x.bound == y.bound);
    CHECK(x.usages[0].cost == y.usages[0].cost);
    CHECK(now.write_cache_fill() == 0.0);
    const double t = write_time(sim_now, now, 0.0, 1'234'567'891);
    CHECK(t == write_time(sim_before, before, 0.0, 1'234'567'891));
    CHECK(t == Approx(1'234'567'891 / (400 * MB)).epsilon(1e-12));
  }
}

TEST_CASE("a write cache comes with the medium's rate behind it, no faster than the writes", "[devices][write_cache]") {
  Simulator sim;
  FairShare share(sim);
  CHECK_THROWS_AS(Disk(share, "x", DiskBandwidth{.read = 1 * GB, .write = 1 * GB, .write_cache = 1'000'000}), ConfigError);
  CHECK_THROWS_AS(Disk(share, "x", DiskBandwidth{.read = 1 * GB, .write = 1 * GB, .sustained_write = 100 * MB}), ConfigError);
  CHECK_THROWS_AS(Disk(share, "x", DiskBandwidth{.read = 1 * GB, .write = 1 * GB, .write_cache = 1'000'000, .sustained_write = 2 * GB}),
                  ConfigError);
  CHECK_THROWS_AS(Disk(share, "x", DiskBandwidth{.read = 1 * GB, .write = 1 * GB, .write_cache = -1, .sustained_write = 100 * MB}),
                  ConfigError);
  // A medium as fast as the cache: the cache changes nothing.
  const Disk same(share, "same", DiskBandwidth{.read = 1 * GB, .write = 1 * GB, .write_cache = 1'000'000, .sustained_write = 1 * GB});
  CHECK(write_time(sim, same, 0.0, 3'000'000'000) == Approx(3.0).epsilon(1e-12));
}
