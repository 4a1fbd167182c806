// A Host's page cache, I/O controller and flusher together, in a simulation. Expected times
// are derived in comments.
#include <pagecache/error.hpp>
#include <pagecache/host.hpp>

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <tuple>
#include <vector>

using namespace pagecache;

namespace {

constexpr std::int64_t MB = 1'000'000;

// 10 GB of memory; disk 100 MB/s; memory copies 1000 MB/s (one channel).
HostSpec small_host(CacheSettings cache = CacheSettings::paper()) {
  return HostSpec{.name = "h",
                  .cores = 4,
                  .memory = 10'000 * MB,
                  .memory_bandwidth = MemoryBandwidth::shared_channel(1000e6),
                  .cache = cache};
}

// The kernel's behaviour with ratios 0.4 and 0.1: on the 10 GB host with no application
// memory, background threshold 1 GB, freerun ceiling 2.5 GB, setpoint 3.25 GB, limit 4 GB.
CacheSettings kernel_04_01() {
  CacheSettings settings = CacheSettings::kernel();
  settings.dirty_ratio = 0.4;
  settings.dirty_background_ratio = 0.1;
  return settings;
}

Task<void> write_then_record(Simulator& sim, Host& host, FileRef file, double& done) {
  co_await host.write_file(file, 100 * MB);
  done = sim.now();
}

}  // namespace

TEST_CASE("dirty data is written back by the flusher once older than dirty_expire", "[host][flusher]") {
  // 500 MB written in cache at 1000 MB/s: done at 0.5 s, dirty since then. Ticks every 5 s
  // from 0; the first tick whose cutoff (tick - 30 s) reaches 0.5 s is at 35 s. The flusher
  // then writes 500 MB at 100 MB/s: done at 40 s, and parks: the simulation ends.
  Simulator sim;
  FairShare share(sim);
  Host host(sim, share, small_host());
  const FileRef file = host.add_file("out", 500 * MB, host.add_disk("d", 100e6, 100e6));
  double written = 0;
  sim.spawn(write_then_record(sim, host, file, written));
  sim.run_until(34.9);
  CHECK(written == Catch::Detail::Approx(0.5));
  CHECK(host.dirty(file) == 500 * MB);
  sim.run();
  CHECK(sim.now() == Catch::Detail::Approx(40.0));
  CHECK(host.memory().dirty == 0);
  CHECK(host.memory().writeback == 0);
  CHECK(host.periodic_flush_bytes() == 500 * MB);
  CHECK(host.cached(file) == 500 * MB);
}

TEST_CASE("a cached file is read again at memory speed", "[host]") {
  // 1 GB from disk at 100 MB/s: 10 s. Read again (buffers released in between): all of it is
  // cached, read from memory at 1000 MB/s: 1 s.
  Simulator sim;
  FairShare share(sim);
  Host host(sim, share, small_host());
  const FileRef file = host.add_file("in", 1000 * MB, host.add_disk("d", 100e6, 100e6));
  std::vector<IoResult> reads;
  auto twice = [](Host& h, FileRef f, std::vector<IoResult>& out) -> Task<void> {
    for (int i = 0; i < 2; ++i) {
      out.push_back(co_await h.read_file(f, 100 * MB));
      h.release_memory(out.back().bytes);
    }
  };
  sim.spawn(twice(host, file, reads));
  sim.run();
  REQUIRE(reads.size() == 2);
  CHECK(reads[0].end - reads[0].start == Catch::Detail::Approx(10.0));
  CHECK(reads[0].disk_bytes == 1000 * MB);
  CHECK(reads[1].end - reads[1].start == Catch::Detail::Approx(1.0));
  CHECK(reads[1].cache_bytes == 1000 * MB);
  CHECK(host.memory().anonymous == 0);
}

TEST_CASE("in writethrough mode a write goes to disk and leaves clean data in the cache", "[host]") {
  // 500 MB through to a 100 MB/s disk: 5 s; then cached clean, nothing dirty.
  CacheSettings settings = CacheSettings::paper();
  settings.write_mode = WriteMode::Writethrough;
  Simulator sim;
  FairShare share(sim);
  Host host(sim, share, small_host(settings));
  const FileRef file = host.add_file("out", 500 * MB, host.add_disk("d", 100e6, 100e6));
  double written = 0;
  sim.spawn(write_then_record(sim, host, file, written));
  sim.run();
  CHECK(written == Catch::Detail::Approx(5.0));
  CHECK(host.cached(file) == 500 * MB);
  CHECK(host.memory().dirty == 0);
}

TEST_CASE("a read that cannot fit in memory fails with the simulated time", "[host]") {
  // 12 GB of application buffers on a 10 GB host.
  Simulator sim;
  FairShare share(sim);
  Host host(sim, share, small_host());
  const FileRef file = host.add_file("huge", 12'000 * MB, host.add_disk("d", 1000e6, 1000e6));
  auto reader = [](Host& h, FileRef f) -> Task<void> { (void)co_await h.read_file(f, 100 * MB); };
  sim.spawn(reader(host, file));
  CHECK_THROWS_WITH(sim.run(), Catch::Contains("t = ") && Catch::Contains("huge"));
}

TEST_CASE("a file larger than its disk is refused", "[host]") {
  Simulator sim;
  FairShare share(sim);
  Host host(sim, share, small_host());
  const DiskRef disk = host.add_disk("small", 100e6, 100e6, 1000 * MB);
  CHECK_THROWS_AS(host.add_file("big", 2000 * MB, disk), ConfigError);
}

TEST_CASE("a bad read or write request is refused at the call", "[host][errors]") {
  Simulator sim;
  FairShare share(sim);
  Host host(sim, share, small_host());
  const FileRef file = host.add_file("local", 100 * MB, host.add_disk("d", 100e6, 100e6));
  CHECK_THROWS_WITH(host.read_file(file, 0), Catch::Contains("chunk size must be > 0"));
  CHECK_THROWS_WITH(host.write_file(file, -1), Catch::Contains("chunk size must be > 0"));
  CHECK_THROWS_WITH(host.read_file(FileRef{7}, 10 * MB), Catch::Contains("unknown file #7"));
  CHECK_THROWS_AS(host.read_file(file, 0), ConfigError);
}

namespace {

Task<void> read_twice_direct(Simulator& sim, Host& client, FileRef file, std::vector<IoResult>& reads) {
  for (int i = 0; i < 2; ++i) {
    reads.push_back(co_await client.read_file(file, 100 * MB, true));
    client.release_memory(reads.back().bytes);
  }
  (void)sim;
}

}  // namespace

TEST_CASE("direct I/O on an NFS mount bypasses the client's cache, not the server's", "[host][features][nfs]") {
  // 500 MB on the server's 100 MB/s disk, over a 1000 MB/s link. The first read comes from the
  // server's disk (5 s) and fills the server's cache; the second comes from that cache, paced
  // by the copies (memory at 1000 MB/s per host: 0.5 s). The client caches nothing.
  Simulator sim;
  FairShare share(sim);
  Host client(sim, share, small_host());
  Host server(sim, share, small_host());
  const FileRef exported = server.add_file("exported", 500 * MB, server.add_disk("d", 100e6, 100e6));
  const Link link(share, "l", 1000e6, 0.0);
  const FileRef remote = client.add_remote_file(server, exported, link);
  std::vector<IoResult> reads;
  sim.spawn(read_twice_direct(sim, client, remote, reads));
  sim.run_until(100.0);
  REQUIRE(reads.size() == 2);
  CHECK(reads[0].end - reads[0].start == Approx(5.0).epsilon(1e-6));
  CHECK(reads[1].end - reads[1].start == Approx(0.5).epsilon(1e-6));
  CHECK(reads[0].cache_bytes == 0);
  CHECK(reads[1].disk_bytes == 500 * MB);  // from the client's side: not from its own cache
  CHECK(client.cached(remote) == 0);
  CHECK(server.cached(exported) == 500 * MB);
  CHECK(client.memory().anonymous == 0);
}

namespace {

Task<void> random_app(Simulator& sim, Host& host, std::vector<FileRef> files, std::uint64_t seed, int tasks,
                      int& finished) {
  std::mt19937_64 rng(seed);
  auto pick = [&](std::size_t n) { return std::uniform_int_distribution<std::size_t>(0, n - 1)(rng); };
  const std::int64_t chunks[] = {10 * MB, 64 * MB, 100 * MB, 333 * MB};
  for (int t = 0; t < tasks; ++t) {
    const FileRef in = files[pick(files.size())];
    const FileRef out = files[pick(files.size())];
    const IoResult read = co_await host.read_file(in, chunks[pick(4)]);
    REQUIRE(read.bytes == host.file_size(in));
    REQUIRE(read.cache_bytes + read.disk_bytes == read.bytes);
    co_await host.compute(static_cast<double>(pick(5)));
    const IoResult write = co_await host.write_file(out, chunks[pick(4)]);
    REQUIRE(write.bytes == host.file_size(out));
    host.release_memory(read.bytes);
    co_await sim.sleep(static_cast<double>(pick(40)));
  }
  ++finished;
}

}  // namespace

TEST_CASE("concurrent applications under memory pressure keep every invariant", "[host][random]") {
  // 8 applications read and write random files of 0.3-1.5 GB (16 files, about 14 GB) through
  // a 16 GB host, holding up to 12 GB of buffers, with random chunk sizes and pauses; every
  // page-cache invariant is checked after every operation. At the end all buffers are
  // released and the flusher has written everything.
  for (const CacheSettings& settings : {CacheSettings::paper(), CacheSettings::kernel()}) {
    for (std::uint64_t seed : {1u, 2u}) {
      Simulator sim;
      FairShare share(sim);
      HostSpec spec = small_host(settings);
      spec.memory = 16'000 * MB;
      Host host(sim, share, spec);
      host.set_checking(true);
      const DiskRef disk = host.add_disk("d", 200e6, 150e6);
      std::mt19937_64 rng(seed);
      std::vector<FileRef> files;
      for (int f = 0; f < 16; ++f) {
        const std::int64_t size = (300 + static_cast<std::int64_t>(rng() % 1200)) * MB;
        files.push_back(host.add_file(fmt::format("f{}", f), size, disk, f % 4 == 0));
      }
      int finished = 0;
      for (int app = 0; app < 8; ++app) sim.spawn(random_app(sim, host, files, seed * 100 + app, 4, finished));
      sim.run();
      CHECK(finished == 8);
      INFO("evicted " << host.evicted_bytes() << " forced flush " << host.forced_flush_bytes());
      CHECK(host.evicted_bytes() > 0);  // the memory pressure was real
      host.check_invariants();
      const MemoryState m = host.memory();
      CHECK(m.anonymous == 0);
      CHECK(m.reserved == 0);
      CHECK(m.dirty == 0);
      CHECK(m.writeback == 0);
      CHECK(m.free + m.cached == m.total);
    }
  }
}

TEST_CASE("background writeback starts above dirty_background_ratio, not at expiry", "[host][flusher]") {
  // 10 GB host, no application memory: dirtyable memory is 10 GB, the background threshold
  // 1 GB (ratio 0.1). 2 GB are written at 1000 MB/s (0-2 s). With background writeback the
  // flusher starts as soon as dirty data passes 1 GB (1.1 s) and writes the oldest data at
  // 100 MB/s until 1 GB or less is left: about 1 GB, so by 12.5 s dirty + writeback <= 1 GB
  // plus one block. Without it, all 2 GB stay dirty until they expire (30 s).
  for (const bool background : {true, false}) {
    CacheSettings settings = kernel_04_01();
    settings.set("background_writeback", background);
    Simulator sim;
    FairShare share(sim);
    Host host(sim, share, small_host(settings));
    const FileRef file = host.add_file("out", 2000 * MB, host.add_disk("d", 100e6, 100e6));
    double written = 0;
    sim.spawn(write_then_record(sim, host, file, written));
    sim.run_until(12.5);
    CHECK(written == Catch::Detail::Approx(2.0));
    const MemoryState m = host.memory();
    INFO("background " << background << ": dirty " << m.dirty << ", writeback " << m.writeback);
    if (background) {
      CHECK(m.dirty + m.writeback <= 1100 * MB);
      CHECK(m.dirty + m.writeback >= 900 * MB);
    } else {
      CHECK(m.dirty == 2000 * MB);
    }
    sim.run();
    CHECK(host.memory().dirty == 0);
  }
}

TEST_CASE("reading a file whose copy and buffer exceed memory needs reclaim of the file itself", "[host]") {
  // 10 GB host, a 6 GB file: 6 GB of buffer + 6 GB of cache do not fit. The kernel reclaims the
  // file's own oldest pages and the read ends at disk speed (6 GB at 1000 MB/s: 6 s); the
  // paper's Algorithm 2 spares the file being read and cannot go on.
  for (const bool may_take : {true, false}) {
    CacheSettings settings = CacheSettings::paper();
    settings.set("reclaim_may_take_file_being_read", may_take);  // the kernel policy's, the others as the paper's
    Simulator sim;
    FairShare share(sim);
    Host host(sim, share, small_host(settings));
    const FileRef file = host.add_file("big", 6000 * MB, host.add_disk("d", 1000e6, 1000e6));
    auto reader = [](Host& h, FileRef f) -> Task<void> { (void)co_await h.read_file(f, 100 * MB); };
    sim.spawn(reader(host, file));
    if (may_take) {
      sim.run();
      CHECK(sim.now() == Catch::Detail::Approx(6.0));
      CHECK(host.cached(file) == 4000 * MB);  // what is left beside the 6 GB buffer
    } else {
      CHECK_THROWS_WITH(sim.run(), Catch::Contains("reading 'big'"));
    }
  }
}

TEST_CASE("fsync returns when the file's dirty data is on disk", "[host][features]") {
  // 500 MB written into the cache at 1000 MB/s (0.5 s), then fsync: 500 MB at 100 MB/s, 5 s.
  Simulator sim;
  FairShare share(sim);
  Host host(sim, share, small_host(CacheSettings::kernel()));
  const FileRef file = host.add_file("out", 500 * MB, host.add_disk("d", 100e6, 100e6));
  double synced = 0;
  auto writer = [](Simulator& s, Host& h, FileRef f, double& done) -> Task<void> {
    co_await h.write_file(f, 100 * MB);
    co_await h.fsync(f);
    done = s.now();
  };
  sim.spawn(writer(sim, host, file, synced));
  sim.run_until(5.4);
  CHECK(synced == 0.0);
  sim.run();
  CHECK(synced == Catch::Detail::Approx(5.5));
  CHECK(host.dirty(file) == 0);
  CHECK(host.cached(file) == 500 * MB);
}

TEST_CASE("direct I/O bypasses the page cache", "[host][features]") {
  // 1 GB read twice with O_DIRECT: both from disk at 100 MB/s (10 s each), nothing cached;
  // then written directly: 10 s at 100 MB/s, nothing dirty.
  Simulator sim;
  FairShare share(sim);
  Host host(sim, share, small_host(CacheSettings::kernel()));
  const DiskRef disk = host.add_disk("d", 100e6, 100e6);
  const FileRef in = host.add_file("in", 1000 * MB, disk);
  const FileRef out = host.add_file("out", 1000 * MB, disk);
  std::vector<IoResult> results;
  auto app = [](Host& h, FileRef i, FileRef o, std::vector<IoResult>& r) -> Task<void> {
    for (int k = 0; k < 2; ++k) {
      r.push_back(co_await h.read_file(i, 100 * MB, true));
      h.release_memory(r.back().bytes);
    }
    r.push_back(co_await h.write_file(o, 100 * MB, true));
  };
  sim.spawn(app(host, in, out, results));
  sim.run();
  REQUIRE(results.size() == 3);
  for (const IoResult& r : results) {
    CHECK(r.end - r.start == Catch::Detail::Approx(10.0));
    CHECK(r.disk_bytes == 1000 * MB);
  }
  CHECK(host.memory().cached == 0);
}

TEST_CASE("a deleted file's dirty data is discarded, never written", "[host][features]") {
  // 500 MB written (dirty), then the file is deleted before it expires: the cache is empty,
  // and the flusher writes nothing.
  Simulator sim;
  FairShare share(sim);
  Host host(sim, share, small_host(CacheSettings::kernel()));
  const FileRef file = host.add_file("tmp", 500 * MB, host.add_disk("d", 100e6, 100e6));
  auto app = [](Host& h, FileRef f) -> Task<void> {
    co_await h.write_file(f, 100 * MB);
    co_await h.delete_file(f);
  };
  sim.spawn(app(host, file));
  sim.run();
  CHECK(host.cached(file) == 0);
  CHECK(host.memory().dirty == 0);
  CHECK(host.periodic_flush_bytes() == 0);
  CHECK(sim.now() == Catch::Detail::Approx(5.0));  // the flusher's next tick, which finds nothing
}

TEST_CASE("dirty throttling holds writers at the kernel's setpoint and paces them at the disk's speed", "[host][throttling]") {
  // 10 GB host, no application memory: dirtyable memory is 10 GB; dirty_ratio 0.4 and
  // dirty_background_ratio 0.1 put the background threshold at 1 GB, the limit at 4 GB, the
  // freerun ceiling at 2.5 GB and the setpoint at (2.5 + 4) / 2 = 3.25 GB. 6 GB are written
  // in 100 MB chunks at 1000 MB/s. Background writeback starts when dirty data passes 1 GB
  // (1.1 s) and writes one 100 MB block a second (100 MB/s). The writer runs free until
  // dirty + writeback are within a chunk of 3.25 GB (3.35 s: 3350 MB written, 200 MB written
  // back); then it is paced, a chunk at a time, at the disk's 100 MB/s times the position
  // ratio (1 at the setpoint, above 1 below it, below 1 above it): dirty + writeback stays
  // within a chunk (100 MB) of the setpoint, and the writer ends when 6000 - 3250 MB, give or
  // take a chunk, are written back, plus at most one chunk's pacing (1 s): between 1.1 + 26.5
  // and 1.1 + 28.5 + 1 s. It never flushes itself. Without throttling (the paper's
  // writer) it runs to dirty_ratio (4 GB) and then flushes a chunk's worth itself before
  // each chunk.
  for (const bool throttling : {true, false}) {
    CacheSettings settings = kernel_04_01();
    settings.set("dirty_throttling", throttling);
    Simulator sim;
    FairShare share(sim);
    Host host(sim, share, small_host(settings));
    std::int64_t peak = 0;
    host.set_memory_observer([&peak](double, const MemoryState& m) { peak = std::max(peak, m.dirty + m.writeback); });
    const FileRef file = host.add_file("out", 6000 * MB, host.add_disk("d", 100e6, 100e6));
    double written = 0;
    sim.spawn(write_then_record(sim, host, file, written));
    sim.run();
    INFO("throttling " << throttling << ": done at " << written << " s, peak dirty + writeback " << peak);
    if (throttling) {
      CHECK(written >= 27.6);
      CHECK(written <= 30.6);
      CHECK(peak <= 3350 * MB);
      CHECK(peak >= 3150 * MB);
      CHECK(host.forced_flush_bytes() == 0);
    } else {
      CHECK(peak > 3900 * MB);
      CHECK(host.forced_flush_bytes() > 0);
    }
    CHECK(host.memory().dirty == 0);
  }
}

TEST_CASE("several throttled writers share the disk's pace", "[host][throttling]") {
  // Two writers of 3 GB each on the host above: together they dirty 1000 MB/s (the one memory
  // channel, 500 MB/s each) until the setpoint (3.25 GB), then each is paced at half the
  // disk's 100 MB/s times the position ratio. They end as one writer of 6 GB would (between
  // 27.6 and 30.6 s, see above), and together: the kernel gives every throttled writer of a
  // device the same rate, so neither is more than a chunk's pacing at half the disk (2 s)
  // behind the other.
  const CacheSettings settings = kernel_04_01();
  Simulator sim;
  FairShare share(sim);
  Host host(sim, share, small_host(settings));
  const DiskRef disk = host.add_disk("d", 100e6, 100e6);
  const FileRef a = host.add_file("a", 3000 * MB, disk);
  const FileRef b = host.add_file("b", 3000 * MB, disk);
  double done_a = 0, done_b = 0;
  sim.spawn(write_then_record(sim, host, a, done_a));
  sim.spawn(write_then_record(sim, host, b, done_b));
  sim.run();
  INFO("a done at " << done_a << " s, b at " << done_b << " s");
  CHECK(std::max(done_a, done_b) >= 27.6);
  CHECK(std::max(done_a, done_b) <= 30.6);
  CHECK(std::abs(done_a - done_b) <= 2.0);
  CHECK(host.forced_flush_bytes() == 0);
}

TEST_CASE("the throttling limit follows a shrinking memory down slowly", "[host][throttling]") {
  // 10 GB host; a 5 GB file is in the cache at rest, so the domain's limit starts at 0.4 x 10
  // GB = 4 GB. The application reads it (5 s at 1000 MB/s) and keeps its 5 GB buffer:
  // dirtyable memory is now 5 GB, the threshold 2 GB, the freerun ceiling (0.5 + 2) / 2 = 1.25
  // GB and the setpoint of the current threshold (1.25 + 2) / 2 = 1.625 GB. Then it writes 6
  // GB (100 MB chunks, disk 100 MB/s). The limit only falls while the writer is above the
  // freerun ceiling, by 1/32 of its distance to the threshold per 200 ms: at first the
  // setpoint is (1.25 + 4) / 2 = 2.6 GB, and dirty data climbs to about 2.4 GB (1.15 GB past
  // the freerun ceiling at 1 GB/s: about 6 updates, the limit at 3.6 GB). After 30 s of
  // throttling (150 updates) the limit is within 1 % of the threshold, and dirty data comes
  // down toward the 1.625 GB setpoint, slowly: the position ratio is flat near it (0.9 at
  // 175 MB above, so the writer goes at 90 MB/s against writeback's 100): between 40 and
  // 45 s it is within 225 MB above the setpoint.
  const CacheSettings settings = kernel_04_01();
  Simulator sim;
  FairShare share(sim);
  Host host(sim, share, small_host(settings));
  const DiskRef disk = host.add_disk("d", 100e6, 100e6);
  const FileRef in = host.add_file("in", 5000 * MB, disk, true);
  const FileRef out = host.add_file("out", 6000 * MB, disk);
  std::int64_t peak = 0;
  std::int64_t late = 0;
  host.set_memory_observer([&](double t, const MemoryState& m) {
    peak = std::max(peak, m.dirty + m.writeback);
    if (t > 40.0 && t < 45.0) late = std::max(late, m.dirty + m.writeback);
  });
  auto app = [](Host& h, FileRef i, FileRef o) -> Task<void> {
    (void)co_await h.read_file(i, 100 * MB);
    co_await h.write_file(o, 100 * MB);
  };
  sim.spawn(app(host, in, out));
  sim.run();
  INFO("peak " << peak << ", between 40 and 45 s " << late);
  CHECK(peak >= 2300 * MB);
  CHECK(peak <= 2600 * MB);
  CHECK(late <= 1850 * MB);
  CHECK(late >= 1625 * MB);
  CHECK(host.forced_flush_bytes() == 0);
}

TEST_CASE("the first touch of fresh memory slows reads into new buffers, not reads paced by the disk", "[host][fresh-memory]") {
  // Copies run at 1000 MB/s and the first touch of fresh memory at 1000 MB/s: a reader fills
  // a new buffer at 1 / (1 / 1000 + 1 / 1000) = 500 MB/s. A 1 GB file on a 100 MB/s disk is
  // read in 10 s, as without the cost (readahead overlaps it); read again from the cache into
  // a new buffer, it takes 2 s instead of 1 s. From a 2000 MB/s disk the reader, not the
  // disk, sets the pace: 2 s instead of 0.5 s.
  for (const double first_touch : {0.0, 1000e6}) {
    for (const double disk_bw : {100e6, 2000e6}) {
      HostSpec spec = small_host(CacheSettings::kernel());
      spec.memory_bandwidth.first_touch = first_touch;
      Simulator sim;
      FairShare share(sim);
      Host host(sim, share, spec);
      const FileRef file = host.add_file("in", 1000 * MB, host.add_disk("d", disk_bw, disk_bw));
      std::vector<IoResult> reads;
      auto twice = [](Host& h, FileRef f, std::vector<IoResult>& out) -> Task<void> {
        for (int i = 0; i < 2; ++i) {
          out.push_back(co_await h.read_file(f, 100 * MB));
          h.release_memory(out.back().bytes);
        }
      };
      sim.spawn(twice(host, file, reads));
      sim.run();
      REQUIRE(reads.size() == 2);
      INFO("first touch " << first_touch << ", disk " << disk_bw);
      const double from_disk = first_touch > 0 ? std::max(10.0 * 100e6 / disk_bw, 2.0) : 10.0 * 100e6 / disk_bw;
      CHECK(reads[0].end - reads[0].start == Catch::Detail::Approx(from_disk));
      CHECK(reads[1].cache_bytes == 1000 * MB);
      CHECK(reads[1].end - reads[1].start == Catch::Detail::Approx(first_touch > 0 ? 2.0 : 1.0));
    }
  }
}

TEST_CASE("written data goes into free pages at one rate and into reclaimed pages at another", "[host][fresh-memory]") {
  // The 10 GB host with 9.5 GB of an old file cached at start (clean): 500 MB free. 800 MB are
  // written in 100 MB chunks, far under the dirty limits (ratio 0.9 of ~10 GB). The first
  // five chunks fill free pages at memory_write_bw, 1000 MB/s: 0.5 s. Each of the last three
  // first evicts 100 MB of the old file and fills those pages at memory_reclaimed_write_bw,
  // 250 MB/s: 1.2 s. The write takes 1.7 s; with the rate unset (0: as free pages), 0.8 s.
  // The same under the paper's Algorithm 3 and under the kernel's throttling. A host with
  // nothing cached writes into free pages only: 0.8 s either way.
  for (const bool kernel : {true, false}) {
    for (const double reclaimed_write : {0.0, 250e6}) {
      for (const bool old_cached : {true, false}) {
        CacheSettings settings = kernel ? CacheSettings::kernel() : CacheSettings::paper();
        settings.dirty_ratio = 0.9;
        settings.dirty_background_ratio = 0.8;
        HostSpec spec = small_host(settings);
        spec.memory_bandwidth.reclaimed_write = reclaimed_write;
        Simulator sim;
        FairShare share(sim);
        Host host(sim, share, spec);
        host.set_checking(true);
        const DiskRef disk = host.add_disk("d", 100e6, 100e6);
        if (old_cached) host.add_file("old", 9500 * MB, disk, true);
        const FileRef file = host.add_file("new", 800 * MB, disk);
        IoResult written;
        auto write = [](Host& h, FileRef f, IoResult& out) -> Task<void> { out = co_await h.write_file(f, 100 * MB); };
        sim.spawn(write(host, file, written));
        sim.run_until(10.0);
        INFO("kernel " << kernel << ", reclaimed write " << reclaimed_write << ", old cached " << old_cached);
        CHECK(written.cache_bytes == 800 * MB);
        CHECK(written.end - written.start == Catch::Detail::Approx(reclaimed_write > 0 && old_cached ? 1.7 : 0.8));
        CHECK(host.cached(file) == 800 * MB);
      }
    }
  }
  Simulator sim;
  FairShare share(sim);
  CHECK_THROWS_AS(Memory(share, "m", MemoryBandwidth{1e9, 1e9, 1e9, 1e9, 0.0, -1.0}), ConfigError);
}

TEST_CASE("two-touch activation: a file written and then read once in chunks has nothing active", "[host][activation]") {
  // Kernel (mark_page_accessed): written pages are not referenced; one read references each
  // page once, and activates none. A read in chunks touches each page once: chunk k must not
  // touch again the pages chunk k - 1 only marked (which would activate every other chunk).
  // Read a second time, every page was referenced: all of it is activated (the lists are
  // then balanced, active <= 2 x inactive: a third moves back, active 1 GB less (1 GB + 2) / 3).
  // WRENCH-cache activates at the first re-read.
  for (const bool two_touch : {true, false}) {
    CacheSettings settings = CacheSettings::kernel();
    settings.set("two_touch_activation", two_touch);
    Simulator sim;
    FairShare share(sim);
    Host host(sim, share, small_host(settings));
    const FileRef file = host.add_file("f", 1000 * MB, host.add_disk("d", 100e6, 100e6));
    std::vector<std::int64_t> active;
    auto write_read_read = [](Host& h, FileRef f, std::vector<std::int64_t>& out) -> Task<void> {
      co_await h.write_file(f, 64 * MB);
      for (int i = 0; i < 2; ++i) {
        const IoResult r = co_await h.read_file(f, 64 * MB);
        h.release_memory(r.bytes);
        out.push_back(h.memory().active);
      }
    };
    sim.spawn(write_read_read(host, file, active));
    sim.run();
    REQUIRE(active.size() == 2);
    INFO("two_touch " << two_touch);
    CHECK(active[0] == (two_touch ? 0 : 666'666'666));
    CHECK(active[1] == 666'666'666);
  }
}

TEST_CASE("a copy out of the page cache waits for a core while a computation holds it", "[host][copies_hold_cores]") {
  // 1 GB cached, read in 100 MB chunks at 1 GB/s (one thread's copy); beside it a task
  // computing 1 core-second. Copies holding cores, on 1 core: the copy (weight 1 GB/s per
  // core) and the computation (weight 1) share the core, half each: the read at 500 MB/s and
  // the computation at half a core, both done at 2 s. On 2 cores each has its own: 1 s. With
  // the switch off the copy needs no core: 1 s on 1 core too.
  for (const auto& [cores, hold, expected] : {std::tuple{1, true, 2.0}, std::tuple{2, true, 1.0}, std::tuple{1, false, 1.0}}) {
    CacheSettings settings = CacheSettings::kernel();
    settings.set("copies_hold_cores", hold);
    HostSpec spec = small_host(settings);
    spec.cores = cores;
    Simulator sim;
    FairShare share(sim);
    Host host(sim, share, spec);
    const FileRef file = host.add_file("cached", 1000 * MB, host.add_disk("d", 100e6, 100e6), true);
    double read_done = 0, compute_done = 0;
    auto read = [](Simulator& s, Host& h, FileRef f, double& done) -> Task<void> {
      const IoResult r = co_await h.read_file(f, 100 * MB);
      CHECK(r.cache_bytes == 1000 * MB);
      done = s.now();
    };
    auto compute = [](Simulator& s, Host& h, double& done) -> Task<void> {
      co_await h.compute(1.0);
      done = s.now();
    };
    sim.spawn(read(sim, host, file, read_done));
    sim.spawn(compute(sim, host, compute_done));
    sim.run();
    INFO(cores << " cores, copies_hold_cores " << hold);
    CHECK(read_done == Catch::Detail::Approx(expected).epsilon(1e-9));
    CHECK(compute_done == Catch::Detail::Approx(expected).epsilon(1e-9));
  }
}

TEST_CASE("a client's read over NFS touches each page of the server's cache once", "[host][activation][nfs]") {
  // 1 GB cached on the server from the start (not referenced). A client reads it once in
  // 100 MB chunks: under two-touch activation the server only marks each page; the chunk
  // requests come one by one, and each must start where the last left off, or every other
  // one would activate what the one before marked. Read a second time: all activated (then
  // balanced: active 1 GB less (1 GB + 2) / 3).
  Simulator sim;
  FairShare share(sim);
  Host client(sim, share, small_host(CacheSettings::kernel()));
  Host server(sim, share, small_host(CacheSettings::kernel()));
  const FileRef exported = server.add_file("exported", 1000 * MB, server.add_disk("d", 100e6, 100e6), true);
  const Link link(share, "l", 1000e6, 0.0);
  const FileRef remote = client.add_remote_file(server, exported, link);
  std::vector<std::int64_t> server_active;
  auto read_twice = [](Host& c, Host& s, FileRef f, std::vector<std::int64_t>& out) -> Task<void> {
    for (int i = 0; i < 2; ++i) {
      const IoResult r = co_await c.read_file(f, 100 * MB, true);  // O_DIRECT: the client caches nothing
      c.release_memory(r.bytes);
      out.push_back(s.memory().active);
    }
  };
  sim.spawn(read_twice(client, server, remote, server_active));
  sim.run();
  REQUIRE(server_active.size() == 2);
  CHECK(server_active[0] == 0);
  CHECK(server_active[1] == 666'666'666);
}
