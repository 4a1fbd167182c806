// A disk's request latency and the kernel's readahead windows (storage/readahead.hpp): each
// expected time and window derived in a comment (the windows from mm/readahead.c's rules, by
// hand), then checked.
#include "storage/readahead.hpp"

#include <pagecache/devices.hpp>
#include <pagecache/error.hpp>

#include <catch2/catch.hpp>

#include <cstdint>
#include <vector>

using namespace pagecache;
using storage::Readahead;

namespace {

constexpr double GB = 1e9;
constexpr double MB = 1e6;
constexpr std::int64_t KiB = 1024;
constexpr std::int64_t MiB = 1024 * KiB;

Task<void> read_direct(Simulator& sim, const Disk& disk, std::int64_t bytes, std::int64_t request, double& finished) {
  co_await disk.read(bytes, kUnbounded, request);
  finished = sim.now();
}

Task<void> write_direct(Simulator& sim, const Disk& disk, std::int64_t bytes, std::int64_t request, double& finished) {
  co_await disk.write(bytes, request);
  finished = sim.now();
}

// A sequential buffered read in chunks, each chunk's device read bounded by its readahead.
Task<void> read_ahead(Simulator& sim, const Disk& disk, std::int64_t bytes, std::int64_t chunk, double& finished) {
  Readahead ra(disk.read_ahead(), disk.max_request(), chunk);
  for (std::int64_t done = 0; done < bytes; done += chunk) {
    co_await disk.read(chunk, static_cast<double>(chunk) / ra.seconds(chunk, disk.request_latency(), disk.read_bandwidth()));
  }
  finished = sim.now();
}

std::vector<std::int64_t> first_windows(const Readahead& ra, int n) {
  std::vector<std::int64_t> out;
  for (int k = 0; k < n; ++k) out.push_back(ra.window(k));
  return out;
}

std::vector<std::int64_t> kib(std::vector<std::int64_t> sizes) {
  for (auto& s : sizes) s *= KiB;
  return sizes;
}

// The time window by window: each whole window latency + window / bandwidth, the last one crossed
// in the share of it the bytes cover.
double naive_seconds(const Readahead& ra, std::int64_t bytes, double latency, double bandwidth) {
  double seconds = 0.0;
  for (std::int64_t k = 0; bytes > 0; ++k) {
    const std::int64_t w = ra.window(k);
    const std::int64_t part = std::min(bytes, w);
    seconds += static_cast<double>(part) / static_cast<double>(w) * (latency + static_cast<double>(w) / bandwidth);
    bytes -= part;
  }
  return seconds;
}

}  // namespace

TEST_CASE("a stream issuing requests one at a time goes at request / (latency + request / bandwidth)", "[devices][requests]") {
  // 0.1 ms per request, 1 GB/s reading, 500 MB/s writing. A 128 KiB request (131072 B) takes
  // 0.1 ms + 131072 / 1e9 s = 231.072 us reading: 131072 / 231.072e-6 B/s; writing
  // 0.1 ms + 262.144 us = 362.144 us.
  Simulator sim;
  FairShare share(sim);
  const Disk disk(share, "nvme", DiskBandwidth{.read = 1 * GB, .write = 500 * MB, .request_latency = 1e-4});
  CHECK(disk.read_request_rate(128 * KiB) == Approx(131072 / 231.072e-6).epsilon(1e-12));
  CHECK(disk.write_request_rate(128 * KiB) == Approx(131072 / 362.144e-6).epsilon(1e-12));
  // No request size (the queue kept full): the stream's rate.
  CHECK(disk.read_request_rate(0) == 1 * GB);
  CHECK(disk.write_request_rate(0) == 500 * MB);
  // No latency: the stream's rate whatever the request.
  const Disk plain(share, "sda", 1 * GB, 500 * MB);
  CHECK(plain.read_request_rate(4 * KiB) == 1 * GB);
  CHECK(plain.write_request_rate(128 * KiB) == 500 * MB);
  CHECK(plain.request_latency() == 0.0);
  CHECK_THROWS_AS(Disk(share, "bad", DiskBandwidth{.read = 1 * GB, .write = 1 * GB, .request_latency = -1e-3}), ConfigError);
  CHECK_THROWS_AS(disk.read(10, kUnbounded, -1), SimulationError);
}

TEST_CASE("a direct read of 1 GB in 128 KiB requests pays the latency once per request", "[devices][requests]") {
  // 1e9 B in requests of 131072 B: 1e9 / 131072 = 7629.39453125 requests (the flow is fluid: the
  // last one in part), each 0.1 ms: 0.762939453125 s, on top of 1e9 B / 1 GB/s = 1 s.
  // Writing at 500 MB/s: 2 s plus the same latency. Writeback (no request size) pays none.
  Simulator sim;
  FairShare share(sim);
  const Disk disk(share, "nvme", DiskBandwidth{.read = 1 * GB, .write = 500 * MB, .request_latency = 1e-4});
  double read_done = 0.0, write_done = 0.0, writeback_done = 0.0;
  sim.spawn(read_direct(sim, disk, 1'000'000'000, 128 * KiB, read_done));
  sim.run();
  CHECK(read_done == Approx(1.762939453125).epsilon(1e-9));
  const double t0 = sim.now();
  sim.spawn(write_direct(sim, disk, 1'000'000'000, 128 * KiB, write_done));
  sim.run();
  CHECK(write_done - t0 == Approx(2.762939453125).epsilon(1e-9));
  const double t1 = sim.now();
  sim.spawn(write_direct(sim, disk, 1'000'000'000, 0, writeback_done));
  sim.run();
  CHECK(writeback_done - t1 == Approx(2.0).epsilon(1e-12));
}

TEST_CASE("the latency holds the stream, not the disk: two direct readers together go twice as fast as one", "[devices][requests]") {
  // A latency of 131072 B / 1 GB/s = 131.072 us: a 128 KiB request takes twice its transfer, so
  // one reader goes at 500 MB/s: 1 GB in 2 s. Two readers of 500 MB each at 500 MB/s use
  // 2 x 0.5 of the disk, exactly all of it: both done at 1 s.
  Simulator sim;
  FairShare share(sim);
  const Disk disk(share, "nvme", DiskBandwidth{.read = 1 * GB, .write = 1 * GB, .request_latency = 131072 / GB});
  double alone = 0.0;
  sim.spawn(read_direct(sim, disk, 1'000'000'000, 128 * KiB, alone));
  sim.run();
  CHECK(alone == Approx(2.0).epsilon(1e-12));
  const double t0 = sim.now();
  double a = 0.0, b = 0.0;
  sim.spawn(read_direct(sim, disk, 500'000'000, 128 * KiB, a));
  sim.spawn(read_direct(sim, disk, 500'000'000, 128 * KiB, b));
  sim.run();
  CHECK(a - t0 == Approx(1.0).epsilon(1e-12));
  CHECK(b - t0 == Approx(1.0).epsilon(1e-12));
}

TEST_CASE("a sequential reader's readahead windows are the kernel's", "[devices][readahead]") {
  // In pages of 4 KiB: read_ahead 128 KiB is ra_pages 32, 8 MiB 2048; max_sectors_kb 1280 KiB
  // is io_pages 320. get_init_ra_size(n, max): n rounded up to a power of two, x4 if <= max/32,
  // x2 if <= max/4, else max. get_next_ra_size(cur, max): x4 if cur < max/16, x2 if
  // cur <= max/2, else max. ractl_max_pages: a read() of more than ra_pages raises max to
  // min(read(), io_pages) when io_pages is above ra_pages.
  const std::int64_t max_request = 1280 * KiB;

  // read() of 4 KiB (1 page), max 32: first 1 <= 1 -> 4 pages (16 KiB); then 4 -> 8 (4 < 2 no,
  // 4 <= 16), 8 -> 16, 16 -> 32 (16 <= 16), 32 -> 32 (32 > 16: max).
  CHECK(first_windows(Readahead(128 * KiB, max_request, 4 * KiB), 6) == kib({16, 32, 64, 128, 128, 128}));
  // max 2048: first 1 <= 64 -> 4; then 4 -> 16, 16 -> 64, 64 -> 256 (all < 128: x4), 256 -> 512,
  // 512 -> 1024, 1024 -> 2048 (<= 1024: x2), 2048 -> 2048.
  CHECK(first_windows(Readahead(8 * MiB, max_request, 4 * KiB), 9) == kib({16, 64, 256, 1024, 2048, 4096, 8192, 8192, 8192}));

  // read() of 128 KiB (32 pages), not more than ra_pages 32: max 32; first 32 (> 1, > 8): max.
  CHECK(first_windows(Readahead(128 * KiB, max_request, 128 * KiB), 3) == kib({128, 128, 128}));
  // max 2048: first 32 <= 64 -> 128 pages (512 KiB); then 128 -> 256 (not < 128; <= 1024),
  // 256 -> 512, 512 -> 1024, 1024 -> 2048, 2048 -> 2048.
  CHECK(first_windows(Readahead(8 * MiB, max_request, 128 * KiB), 7) == kib({512, 1024, 2048, 4096, 8192, 8192, 8192}));

  // read() of 100 MB: 100e6 / 4096 = 24414.06 -> 24415 pages, more than ra_pages 32 and io_pages
  // 320 > 32: max = min(24415, 320) = 320 (1280 KiB); first: 32768 > 80 -> max, and max for good.
  CHECK(first_windows(Readahead(128 * KiB, max_request, 100'000'000), 3) == kib({1280, 1280, 1280}));
  // Against 2048: io_pages 320 is not above it, max stays 2048; first 32768 > 512 -> 2048.
  CHECK(first_windows(Readahead(8 * MiB, max_request, 100'000'000), 3) == kib({8192, 8192, 8192}));
  // No request limit (max_request 0): max = min(24415, unlimited) = 24415 pages.
  CHECK(first_windows(Readahead(128 * KiB, 0, 100'000'000), 2) == std::vector<std::int64_t>{24415 * 4 * KiB, 24415 * 4 * KiB});
  CHECK(Readahead(8 * MiB, max_request, 4 * KiB).max_window() == 8 * MiB);

  CHECK_THROWS_AS(Readahead(0, max_request, 4 * KiB), ConfigError);
  CHECK_THROWS_AS(Readahead(128 * KiB, 512, 4 * KiB), ConfigError);
  CHECK_THROWS_AS(Readahead(128 * KiB, 0, 0), ConfigError);
  Simulator sim;
  FairShare share(sim);
  CHECK_THROWS_AS(Disk(share, "bad", DiskBandwidth{.read = 1 * GB, .write = 1 * GB, .read_ahead = 1000}), ConfigError);
  CHECK_THROWS_AS(Disk(share, "bad", DiskBandwidth{.read = 1 * GB, .write = 1 * GB, .max_request = 2048}), ConfigError);
}

TEST_CASE("the readahead's closed form equals the sum window by window, in one call or chunk by chunk", "[devices][readahead]") {
  const double latency = 1e-4;
  const double bw = 2 * GB;
  for (const auto& [read_ahead, request] : {std::pair{128 * KiB, 4 * KiB}, std::pair{8 * MiB, 128 * KiB}, std::pair{8 * MiB, 4 * KiB}}) {
    for (const std::int64_t bytes : {std::int64_t{4096}, std::int64_t{1'000'000}, std::int64_t{1'000'000'007}, std::int64_t{100'000'000'000}}) {
      INFO(read_ahead << " B readahead, read() of " << request << " B, " << bytes << " B");
      Readahead whole(read_ahead, 1280 * KiB, request);
      const double expected = naive_seconds(whole, bytes, latency, bw);
      CHECK(whole.seconds(bytes, latency, bw) == Approx(expected).epsilon(1e-10));
      CHECK(whole.position() == bytes);
      // Chunks of 3 MiB + 5 B: windows crossed in part, the ramp crossed in one chunk.
      Readahead chunked(read_ahead, 1280 * KiB, request);
      double sum = 0.0;
      for (std::int64_t left = bytes; left > 0;) {
        const std::int64_t chunk = std::min(left, 3 * MiB + 5);
        sum += chunked.seconds(chunk, latency, bw);
        left -= chunk;
      }
      CHECK(sum == Approx(expected).epsilon(1e-9));
    }
  }
  // 100 GB read in 4 KiB read()s against 8 MiB: the 6 windows of the ramp (16, 64, 256, 1024,
  // 2048, 4096 KiB: 7504 KiB), then (1e11 - 7504 KiB) / 8 MiB = 11919.98... windows of 8 MiB.
  Readahead ra(8 * MiB, 1280 * KiB, 4 * KiB);
  const double ramp = static_cast<double>(7504 * KiB);
  const double windows = 6 + (1e11 - ramp) / static_cast<double>(8 * MiB);
  CHECK(ra.seconds(100'000'000'000, latency, bw) == Approx(windows * latency + 1e11 / bw).epsilon(1e-12));
}

TEST_CASE("without latency the readahead leaves the bandwidth", "[devices][readahead]") {
  Readahead ra(128 * KiB, 1280 * KiB, 4 * KiB);
  for (const std::int64_t chunk : {std::int64_t{4096}, std::int64_t{10'000}, std::int64_t{1'000'000'000}}) {
    CHECK(static_cast<double>(chunk) / ra.seconds(chunk, 0.0, 465 * MB) == Approx(465 * MB).epsilon(1e-15));
  }
}

TEST_CASE("a buffered read bounded chunk by chunk by its readahead pays one latency per window", "[devices][readahead]") {
  // read_ahead 128 KiB, read() of 128 KiB: every window 128 KiB (above). 1 GiB is 8192 windows:
  // 8192 x 0.1 ms = 0.8192 s on top of 2^30 / 1 GB/s = 1.073741824 s. In 64 KiB read()s the same:
  // 16 pages are above 32 / 4, so the first window is max already, and each chunk is half a
  // window, paying half its latency.
  for (const std::int64_t chunk : {128 * KiB, 64 * KiB}) {
    Simulator sim;
    FairShare share(sim);
    const Disk disk(share, "nvme", DiskBandwidth{.read = 1 * GB, .write = 1 * GB, .request_latency = 1e-4, .read_ahead = 128 * KiB,
                                                 .max_request = 1280 * KiB});
    double done = 0.0;
    sim.spawn(read_ahead(sim, disk, 1024 * MiB, chunk, done));
    sim.run();
    INFO(chunk << " B chunks");
    CHECK(done == Approx(0.8192 + 1.073741824).epsilon(1e-9));
  }
}
