// Files held by byte range, rule by rule: reads hit exactly what is cached, a partial re-read
// refreshes only what it touches, sequential reads stay a few blocks, eviction takes the
// least recently used bytes; and Host::read_ranges in a simulation (times derived in comments).
#include "cache/page_cache.hpp"

#include <pagecache/error.hpp>
#include <pagecache/host.hpp>

#include <catch2/catch.hpp>

#include <cstdint>
#include <functional>
#include <vector>

using namespace pagecache;
using namespace pagecache::cache;

namespace {

constexpr std::int64_t MB = 1'000'000;

CacheSettings lru() {
  CacheSettings settings = CacheSettings::kernel();
  settings.policy = "lru";
  return settings;
}

// The file's cached ranges, merged where contiguous, by offset.
std::vector<std::pair<std::int64_t, std::int64_t>> held(const PageCache& cache, FileId file) {
  std::vector<std::pair<std::int64_t, std::int64_t>> runs;
  cache.ranges().for_each(file, [&](BlockId id) {
    const std::int64_t offset = cache.ranges().offset(id);
    const std::int64_t end = offset + cache.list(ListKind::Inactive).block(id).size;
    if (!runs.empty() && runs.back().second == offset) runs.back().second = end;
    else runs.emplace_back(offset, end);
  });
  return runs;
}

using Runs = std::vector<std::pair<std::int64_t, std::int64_t>>;

}  // namespace

TEST_CASE("a read of a range hits exactly what is cached of it", "[page_cache][ranges]") {
  PageCache cache(1000, lru());
  cache.set_checking(true);
  cache.track_ranges(0);
  CHECK(cache.read_range(0, 100, 100, 0.0) == 100);  // [100, 200) from the device
  CHECK(cache.ranges().cached_in(0, 0, 1000) == 100);
  CHECK(cache.ranges().cached_in(0, 150, 100) == 50);
  CHECK(cache.read_range(0, 150, 100, 1.0) == 50);  // [150, 200) hits, [200, 250) misses
  CHECK(cache.read_range(0, 0, 300, 2.0) == 150);   // [0, 100) and [250, 300) miss
  CHECK(held(cache, 0) == Runs{{0, 300}});
  CHECK(cache.file(0).cached() == 300);
  CHECK(cache.read_range(0, 0, 300, 3.0) == 0);
}

TEST_CASE("a partial re-read refreshes only the part it touches", "[page_cache][ranges]") {
  PageCache cache(1000, lru());
  cache.set_checking(true);
  cache.track_ranges(0);
  cache.read_range(0, 0, 100, 0.0);
  cache.read_range(0, 20, 10, 1.0);  // [20, 30) to the MRU end
  // Eviction takes the least recently used bytes: [0, 20), then [30, 100), then [20, 30).
  CHECK(cache.evict(20, kNoFile) == 20);
  CHECK(held(cache, 0) == Runs{{20, 100}});
  CHECK(cache.evict(70, kNoFile) == 70);
  CHECK(held(cache, 0) == Runs{{20, 30}});
}

TEST_CASE("a file read in order in small requests stays one block", "[page_cache][ranges]") {
  PageCache cache(100 * MB, CacheSettings::kernel());
  cache.set_checking(false);
  cache.track_ranges(0);
  for (std::int64_t offset = 0; offset < 10 * MB; offset += 4096) cache.read_range(0, offset, std::min<std::int64_t>(4096, 10 * MB - offset), 0.0);
  CHECK(cache.file(0).cached() == 10 * MB);
  CHECK(cache.list(ListKind::Inactive).size() + cache.list(ListKind::Active).size() == 1);
  cache.check_invariants();
}

TEST_CASE("data cached whole before a file is held by range takes offsets from 0, least recently used first", "[page_cache][ranges]") {
  PageCache cache(1000, lru());
  cache.set_checking(true);
  cache.add_read(0, 100, 0.0);
  cache.add_read(1, 50, 0.0);
  cache.add_read(0, 20, 1.0);
  cache.track_ranges(0);
  CHECK(held(cache, 0) == Runs{{0, 120}});
  CHECK_FALSE(cache.ranges().tracked(1));
  CHECK(cache.read_range(0, 100, 50, 2.0) == 30);
}

TEST_CASE("random reads of a file: each a device request for its missing pages, then hits", "[host][ranges]") {
  // 1 GB of memory, a disk of 100 MB/s with 10 ms per request, memory copies at 1000 MB/s.
  // Reads of 4 KiB at 100 distinct page-aligned offsets: each misses and pays 10 ms +
  // 4096 B / 100 MB/s = 10.04096 ms; the same 100 again hit, 4096 B / 1000 MB/s each.
  Simulator sim;
  FairShare share(sim);
  Host host(sim, share,
            HostSpec{.name = "h", .cores = 1, .memory = 1000 * MB, .memory_bandwidth = MemoryBandwidth::shared_channel(1000e6), .cache = lru()});
  DiskBandwidth disk{.read = 100e6, .write = 100e6, .request_latency = 0.01};
  const FileRef file = host.add_file("data", 100 * MB, host.add_disk("d", disk));
  std::vector<ByteRange> requests;
  for (int i = 0; i < 100; ++i) requests.push_back({.offset = (i * 7919 % 24000) * 4096, .length = 4096});
  IoResult first, second;
  auto reader = [&]() -> Task<void> {
    for (IoResult* result : {&first, &second}) {
      std::size_t next = 0;
      *result = co_await host.read_ranges(file, [&](ByteRange& r) { return next < requests.size() && (r = requests[next++], true); }, 4096);
    }
  };
  sim.spawn(reader());
  sim.run();
  CHECK(first.disk_bytes == 100 * 4096);
  CHECK(first.cache_bytes == 0);
  CHECK(first.end - first.start == Approx(100 * (0.01 + 4096 / 100e6)));
  CHECK(second.disk_bytes == 0);
  CHECK(second.cache_bytes == 100 * 4096);
  CHECK(second.end - second.start == Approx(100 * 4096 / 1000e6));
  CHECK(host.cached(file) == 100 * 4096);
  CHECK(host.memory().anonymous == 0);  // the buffer is given back
}

TEST_CASE("a read of part of a page reads the whole page; requests outside the file are refused", "[host][ranges]") {
  Simulator sim;
  FairShare share(sim);
  Host host(sim, share, HostSpec{.name = "h", .cores = 1, .memory = 1000 * MB, .memory_bandwidth = MemoryBandwidth::shared_channel(1000e6), .cache = CacheSettings::kernel()});
  const FileRef file = host.add_file("data", 10'000, host.add_disk("d", 100e6, 100e6));
  IoResult result;
  auto reader = [&](ByteRange only) -> Task<void> {
    bool given = false;
    result = co_await host.read_ranges(file, [&](ByteRange& r) { return !given && (r = only, given = true); }, 100);
  };
  sim.spawn(reader({.offset = 9000, .length = 100}));  // the last page: [8192, 10000)
  sim.run();
  // The request's 100 bytes came from the device, which read (and cached) the whole page.
  CHECK(result.bytes == 100);
  CHECK(result.disk_bytes == 100);
  CHECK(result.cache_bytes == 0);
  CHECK(host.cached(file) == 10'000 - 8192);
  sim.spawn(reader({.offset = 9950, .length = 100}));
  CHECK_THROWS_AS(sim.run(), SimulationError);
  CHECK_THROWS_AS(host.read_ranges(file, [](ByteRange&) { return false; }, 0), ConfigError);
}

namespace {

// A request source over a list.
std::function<bool(ByteRange&)> each(std::vector<ByteRange> requests) {
  return [requests = std::move(requests), next = std::size_t{0}](ByteRange& r) mutable {
    if (next == requests.size()) return false;
    r = requests[next++];
    return true;
  };
}

std::vector<ByteRange> in_order(std::int64_t size, std::int64_t request) {
  std::vector<ByteRange> out;
  for (std::int64_t at = 0; at < size; at += request) out.push_back({.offset = at, .length = std::min(request, size - at)});
  return out;
}

}  // namespace

TEST_CASE("writes by range: in place over what is cached, appends stay one block, fsync writes them", "[host][ranges]") {
  Simulator sim;
  FairShare share(sim);
  Host host(sim, share,
            HostSpec{.name = "h", .cores = 1, .memory = 1000 * MB, .memory_bandwidth = MemoryBandwidth::shared_channel(1000e6), .cache = CacheSettings::kernel()});
  const DiskRef disk = host.add_disk("d", 100e6, 100e6);
  const FileRef data = host.add_file("data", 10 * MB, disk);
  const FileRef log = host.add_file("log", 4 * MB, disk);
  IoResult rewrite, appended;
  std::vector<std::int64_t> seen;  // (cached, dirty) of the file after each step
  // (Lists made outside the coroutine: GCC 12 cannot keep a braced list across a co_await.)
  constexpr std::int64_t kPage = 4096;
  const std::vector<ByteRange> middle{{.offset = 500 * kPage, .length = 700 * kPage}};  // whole pages
  const auto note = [&](FileRef f) {
    seen.push_back(host.cached(f));
    seen.push_back(host.dirty(f));
  };
  auto job = [&]() -> Task<void> {
    co_await host.read_ranges(data, each(in_order(10 * MB, 1 * MB)), 1 * MB);
    // Rewriting the cached file in place: its pages become dirty, none is added; again over
    // the same range, the same.
    rewrite = co_await host.write_ranges(data, each(middle));
    note(data);
    co_await host.write_ranges(data, each(middle));
    note(data);
    // A log appended to in 4 KiB writes, then fsync'd.
    appended = co_await host.write_ranges(log, each(in_order(4 * MB, 4096)));
    note(log);
    co_await host.fsync(log);
    note(log);
  };
  sim.spawn(job());
  sim.run();
  CHECK(seen == std::vector<std::int64_t>{10 * MB, 700 * kPage, 10 * MB, 700 * kPage, 4 * MB, 4 * MB, 4 * MB, 0});
  CHECK(rewrite.bytes == 700 * kPage);
  CHECK(appended.bytes == 4 * MB);
  // The log's 4 MB written back at 100 MB/s took at least 40 ms.
  CHECK(sim.now() > 0.04);
}

TEST_CASE("a file held by range and written whole twice holds its size once", "[host][ranges]") {
  Simulator sim;
  FairShare share(sim);
  Host host(sim, share,
            HostSpec{.name = "h", .cores = 1, .memory = 1000 * MB, .memory_bandwidth = MemoryBandwidth::shared_channel(1000e6), .cache = CacheSettings::kernel()});
  const FileRef file = host.add_file("f", 50 * MB, host.add_disk("d", 100e6, 100e6));
  const std::vector<ByteRange> one_page{{.offset = 0, .length = 4096}};
  auto job = [&]() -> Task<void> {
    co_await host.read_ranges(file, each(one_page), 4096);  // now held by range
    co_await host.write_file(file, 10 * MB);
    co_await host.write_file(file, 10 * MB);
  };
  sim.spawn(job());
  sim.run();
  CHECK(host.cached(file) == 50 * MB);
}

TEST_CASE("sequential requests are read ahead in ramping windows; POSIX_FADV_RANDOM reads each alone", "[host][ranges]") {
  // 10 MiB read in 4 KiB requests from a disk of 100 MB/s, 1 ms a request, read_ahead 128 KiB.
  // Without readahead: 2560 requests of 1 ms + 4096 B / 100 MB/s each, 2.665 s. With it, the
  // kernel's windows: 16, 32, 64 KiB, then 128 KiB (about 83 device requests): 83 ms of
  // latency, 0.105 s of transfer and 10 ms of copies from the cache, about 0.2 s.
  constexpr std::int64_t kMiB = 1 << 20;
  auto read_with = [](ReadAdvice advice) {
    Simulator sim;
    FairShare share(sim);
    Host host(sim, share,
              HostSpec{.name = "h", .cores = 1, .memory = 1000 * MB, .memory_bandwidth = MemoryBandwidth::shared_channel(1000e6), .cache = lru()});
    const FileRef file =
        host.add_file("f", 10 * kMiB, host.add_disk("d", DiskBandwidth{.read = 100e6, .write = 100e6, .request_latency = 0.001, .read_ahead = 128 * 1024}));
    IoResult result;
    const std::vector<ByteRange> requests = in_order(10 * kMiB, 4096);
    auto job = [&]() -> Task<void> { result = co_await host.read_ranges(file, each(requests), 4096, {}, advice); };
    sim.spawn(job());
    sim.run();
    return result;
  };
  const IoResult random = read_with(ReadAdvice::Random);
  CHECK(random.end - random.start == Approx(2560 * (0.001 + 4096 / 100e6)));
  CHECK(random.disk_bytes == 10 * kMiB);
  const IoResult normal = read_with(ReadAdvice::Normal);
  // Every byte from the device during the read, most of them read ahead of the request that
  // found them in the cache (the time below): none was cached before.
  CHECK(normal.disk_bytes == 10 * kMiB);
  CHECK(normal.cache_bytes == 0);
  CHECK(normal.end - normal.start > 0.19);
  CHECK(normal.end - normal.start < 0.21);
  const IoResult doubled = read_with(ReadAdvice::Sequential);
  CHECK(doubled.end - doubled.start < normal.end - normal.start - 0.03);  // about half the windows
}

TEST_CASE("each request of a read by parts costs the host's request_time", "[host][ranges]") {
  // 1000 cached 4 KiB requests at 1000 MB/s take 4.096 ms of copies; with 20 us of system call
  // each, 20 ms more (slept in stretches of 1 ms: the same total).
  auto run = [](double request_time) {
    Simulator sim;
    FairShare share(sim);
    Host host(sim, share,
              HostSpec{.name = "h", .cores = 1, .memory = 1000 * MB, .memory_bandwidth = MemoryBandwidth::shared_channel(1000e6), .cache = lru(),
                       .request_time = request_time});
    const FileRef file = host.add_file("f", 4096 * 1000, host.add_disk("d", 100e6, 100e6), true);
    const std::vector<ByteRange> requests = in_order(4096 * 1000, 4096);
    IoResult result;
    auto job = [&]() -> Task<void> { result = co_await host.read_ranges(file, each(requests), 4096, {}, ReadAdvice::Random); };
    sim.spawn(job());
    sim.run();
    return result.end - result.start;
  };
  CHECK(run(0.0) == Approx(1000 * 4096 / 1000e6));
  CHECK(run(20e-6) == Approx(1000 * 4096 / 1000e6 + 1000 * 20e-6));
}

TEST_CASE("POSIX_FADV_WILLNEED reads ahead in the background; POSIX_FADV_DONTNEED drops the clean pages of a range", "[host][ranges]") {
  // 10 MB at 100 MB/s: the prefetch ends at 0.1 s, while the task computes for 1 s; its read
  // then hits all of it. DONTNEED then drops the 3 MB it names but the 1 MB just written.
  constexpr std::int64_t kMiB = 1 << 20;
  Simulator sim;
  FairShare share(sim);
  Host host(sim, share,
            HostSpec{.name = "h", .cores = 1, .memory = 1000 * MB, .memory_bandwidth = MemoryBandwidth::shared_channel(1000e6), .cache = lru()});
  const FileRef file = host.add_file("f", 10 * kMiB, host.add_disk("d", 100e6, 100e6));
  const std::vector<ByteRange> all = in_order(10 * kMiB, kMiB);
  const std::vector<ByteRange> written{{.offset = 0, .length = kMiB}};
  IoResult read;
  std::vector<std::int64_t> seen;
  auto job = [&]() -> Task<void> {
    host.will_need(file, {.offset = 0, .length = 10 * kMiB});
    co_await host.compute(1.0);
    seen.push_back(host.cached(file));
    read = co_await host.read_ranges(file, each(all), kMiB);
    co_await host.write_ranges(file, each(written));
    seen.push_back(host.dont_need(file, {.offset = 0, .length = 4 * kMiB}));
    seen.push_back(host.cached(file));
    seen.push_back(host.dirty(file));
  };
  sim.spawn(job());
  sim.run();
  CHECK(seen == std::vector<std::int64_t>{10 * kMiB, 3 * kMiB, 7 * kMiB, kMiB});
  CHECK(read.disk_bytes == 0);
  CHECK(read.cache_bytes == 10 * kMiB);
  CHECK_THROWS_AS(host.dont_need(file, {.offset = 10 * kMiB, .length = 1}), SimulationError);
}
