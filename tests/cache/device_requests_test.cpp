// A host's reads and writes in the device's requests (docs/model.md §6.17): buffered reads in
// the kernel's readahead windows, O_DIRECT in the application's request size. Times derived
// in comments.
#include <pagecache/host.hpp>

#include <catch2/catch.hpp>

#include <cstdint>

using namespace pagecache;

namespace {

constexpr std::int64_t MB = 1'000'000;
constexpr std::int64_t KiB = 1024;

HostSpec plain_host() {
  return HostSpec{.name = "h", .cores = 4, .memory = 10'000 * MB, .memory_bandwidth = MemoryBandwidth::shared_channel(1000e6),
                  .cache = CacheSettings::kernel()};
}

// Disk: 100 MB/s read, 50 MB/s write, 1 ms per request (or none), readahead 128 KiB, requests
// of at most 1280 KiB.
DiskBandwidth requests_disk(double latency) {
  return DiskBandwidth{.read = 100e6, .write = 50e6, .request_latency = latency, .read_ahead = 128 * KiB, .max_request = 1280 * KiB};
}

struct Timed {
  double read = 0.0;
  double write = 0.0;
};

// Reads `in` in chunks of `chunk`, then writes `out` the same way; records each one's time.
Task<void> read_then_write(Simulator& sim, Host& host, FileRef in, FileRef out, std::int64_t chunk, bool direct, Timed& t) {
  double start = sim.now();
  const IoResult r = co_await host.read_file(in, chunk, direct);
  t.read = sim.now() - start;
  host.release_memory(r.bytes);
  start = sim.now();
  co_await host.write_file(out, chunk, direct);
  t.write = sim.now() - start;
}

Timed run(double latency, std::int64_t chunk, bool direct) {
  Simulator sim;
  FairShare share(sim);
  Host host(sim, share, plain_host());
  const DiskRef disk = host.add_disk("d", requests_disk(latency));
  const FileRef in = host.add_file("in", 100 * MB, disk);
  const FileRef out = host.add_file("out", 100 * MB, disk);
  Timed t;
  sim.spawn(read_then_write(sim, host, in, out, chunk, direct, t));
  sim.run_until(100.0);
  return t;
}

}  // namespace

TEST_CASE("a sequential buffered read goes at its readahead windows' request rate", "[cache][requests]") {
  // 100 MB read() calls: larger than the 128 KiB readahead, so each window is max_request's
  // 1280 KiB (ractl_max_pages) from the first. 100 MB are 76.29 windows, each 1 ms more than
  // at 100 MB/s: 1 + 0.0762939 s. Without latency: 1 s, as a device without requests.
  CHECK(run(0.001, 100 * MB, false).read == Catch::Detail::Approx(1.0 + 100e6 / (1280.0 * 1024) * 0.001).epsilon(1e-9));
  CHECK(run(0.0, 100 * MB, false).read == Catch::Detail::Approx(1.0).epsilon(1e-12));
  // 16 KiB read() calls: the first window is 32 KiB (get_init_ra_size: 16 KiB is above
  // max / 32 = 4 KiB and at most max / 4 = 32 KiB: doubled), then 64 KiB (get_next_ra_size:
  // doubled up to max / 2), then 128 KiB for good; each window pays a latency.
  const double windows = 2.0 + (100e6 - 96.0 * 1024) / (128.0 * 1024);
  CHECK(run(0.001, 16 * KiB, false).read == Catch::Detail::Approx(1.0 + windows * 0.001).epsilon(1e-9));
}

TEST_CASE("O_DIRECT reads and writes go in the application's requests, each paying the latency", "[cache][requests]") {
  // 1 MB requests: 100 of them, 1 ms + 10 ms each to read (100 MB/s), 1 ms + 20 ms to write.
  const Timed direct = run(0.001, 1 * MB, true);
  CHECK(direct.read == Catch::Detail::Approx(1.1).epsilon(1e-9));
  CHECK(direct.write == Catch::Detail::Approx(2.1).epsilon(1e-9));
  // Without latency the requests do not matter.
  const Timed plain = run(0.0, 1 * MB, true);
  CHECK(plain.read == Catch::Detail::Approx(1.0).epsilon(1e-12));
  CHECK(plain.write == Catch::Detail::Approx(2.0).epsilon(1e-12));
}
