// Reclaim in a memory group against reclaim of the whole host: fio's shape (lay out a file in
// 16 KiB writes, then read it twice in random 16 KiB requests) with the cache held to the same
// size once by a group's memory.max on a large host and once by the host's own memory. A
// group's victims are found as the host's are (its own order of reclaimable files), so the
// cost per chunk operation should be close. Prints JSON: each run's operations, events, wall
// seconds and nanoseconds per operation, and their ratio (group / host).
//   group_reclaim [FILE_MIB]        # default 4096 (a 4 GiB file, a 2 GiB cache)
#include <pagecache/host.hpp>

#include "splitmix64.hpp"

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

using namespace pagecache;

namespace {

constexpr std::int64_t kMiB = 1 << 20;
constexpr std::int64_t kRequest = 16 * 1024;

struct Figures {
  std::int64_t operations = 0;
  unsigned long long events = 0;
  double wall = 0.0;
};

// `in_group`: a 64 GiB host, the job in a group of memory.max = half the file; else a host
// whose memory is that half.
Figures run(std::int64_t file_bytes, bool in_group) {
  const std::int64_t cache = file_bytes / 2;
  Simulator sim;
  FairShare share(sim);
  HostSpec spec;
  spec.name = "node";
  spec.cores = 4;
  spec.memory = in_group ? 64 * 1024 * kMiB : cache;
  spec.memory_bandwidth = MemoryBandwidth::shared_channel(10e9);
  spec.cache = CacheSettings::kernel();
  Host host(sim, share, spec);
  const FileRef file = host.add_file("data", file_bytes, host.add_disk("nvme", DiskBandwidth{.read = 2e9, .write = 1e9, .request_latency = 80e-6}));
  const Thread thread = in_group ? Thread(host.add_memory_group(cache)) : Thread();
  const auto pages = static_cast<std::uint64_t>(file_bytes / kRequest);
  std::uint64_t state = 42;
  Figures f;
  auto job = [&]() -> Task<void> {
    std::int64_t written = 0;
    co_await host.write_ranges(
        file,
        [&](ByteRange& r) {
          if (written == file_bytes) return false;
          r = {.offset = written, .length = kRequest};
          written += kRequest;
          ++f.operations;
          return true;
        },
        thread);
    for (int loop = 0; loop < 2; ++loop) {
      std::uint64_t issued = 0;
      co_await host.read_ranges(
          file,
          [&](ByteRange& r) {
            if (issued == pages) return false;
            ++issued;
            ++f.operations;
            r = {.offset = static_cast<std::int64_t>(bench::splitmix64(state) % pages) * kRequest, .length = kRequest};
            return true;
          },
          kRequest, thread);
    }
  };
  const auto start = std::chrono::steady_clock::now();
  sim.spawn(job());
  sim.run();
  f.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  f.events = sim.events_processed();
  return f;
}

void print(const char* name, const Figures& f) {
  std::printf("  \"%s\": {\"operations\": %lld, \"events\": %llu, \"wall_seconds\": %.3f, \"ns_per_operation\": %.1f},\n", name,
              static_cast<long long>(f.operations), f.events, f.wall, 1e9 * f.wall / static_cast<double>(f.operations));
}

}  // namespace

int main(int argc, char** argv) {
  const std::int64_t file_bytes = (argc > 1 ? std::atoll(argv[1]) : 4096) * kMiB;
  if (file_bytes < 2 * kMiB) {
    std::fprintf(stderr, "group_reclaim: FILE_MIB must be at least 2\n");
    return 2;
  }
  const Figures host = run(file_bytes, false);
  const Figures group = run(file_bytes, true);
  std::printf("{\n  \"file_mib\": %lld,\n", static_cast<long long>(file_bytes / kMiB));
  print("host", host);
  print("group", group);
  std::printf("  \"group_over_host_per_operation\": %.3f\n}\n",
              (group.wall / static_cast<double>(group.operations)) / (host.wall / static_cast<double>(host.operations)));
  return 0;
}
