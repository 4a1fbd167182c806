// Random reads of one large file through Host::read_ranges: the cost of a file held by byte
// range under a cache smaller than the file (issue 38's target: 10^7 random 4 KiB reads over a
// 10 GB file with a 4 GB cache). Prints JSON: requests, events, wall seconds, hit share.
//   random_reads [REQUESTS]
#include <pagecache/host.hpp>

#include "splitmix64.hpp"

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

using namespace pagecache;

int main(int argc, char** argv) {
  const std::int64_t requests = argc > 1 ? std::atoll(argv[1]) : 10'000'000;
  constexpr std::int64_t GB = 1'000'000'000;
  constexpr std::int64_t kPage = 4096;
  Simulator sim;
  FairShare share(sim);
  Host host(sim, share,
            HostSpec{.name = "node", .cores = 4, .memory = 4 * GB, .memory_bandwidth = MemoryBandwidth::shared_channel(10e9),
                     .cache = CacheSettings::kernel()});
  const FileRef file = host.add_file("data", 10 * GB, host.add_disk("nvme", DiskBandwidth{.read = 2e9, .write = 1e9, .request_latency = 80e-6}));
  std::uint64_t state = 42;
  const auto pages = static_cast<std::uint64_t>(10 * GB / kPage);
  std::int64_t issued = 0;
  IoResult result;
  auto reader = [&]() -> Task<void> {
    result = co_await host.read_ranges(
        file,
        [&](ByteRange& r) {
          if (issued == requests) return false;
          ++issued;
          r = {.offset = static_cast<std::int64_t>(bench::splitmix64(state) % pages) * kPage, .length = kPage};
          return true;
        },
        kPage);
  };
  const auto start = std::chrono::steady_clock::now();
  sim.spawn(reader());
  sim.run();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("{\"requests\": %lld, \"events\": %llu, \"wall_seconds\": %.3f, \"simulated_seconds\": %.3f, \"hit_share\": %.4f}\n",
              static_cast<long long>(requests), static_cast<unsigned long long>(sim.events_processed()), wall, sim.now(),
              static_cast<double>(result.cache_bytes) / static_cast<double>(result.bytes));
  return 0;
}
