#pragma once
// Test helpers for the paper's synthetic application: a pipeline of three tasks, task k
// reading file k, computing, writing file k+1, releasing its memory at the end; and the
// paper's platform as WRENCH-cache modelled it (docs/wrench-cache.md).

#include <pagecache/host.hpp>

#include <string>
#include <vector>

namespace pagecache::testing {

struct PhaseRecord {
  int pipeline = 0;
  int task = 0;
  std::string phase;  // read, compute, write
  double start = 0.0;
  double end = 0.0;
  double duration() const { return end - start; }
};

struct CacheRecord {
  int task = 0;
  std::string phase;
  int file = 0;  // 1-based
  std::int64_t cached = 0;
};

inline HostSpec wrench_cache_host() {
  return HostSpec{.name = "host",
                  .cores = 32,
                  .memory = 268'000'000'000,
                  .memory_bandwidth = MemoryBandwidth::shared_channel(4812e6),
                  .cache = CacheSettings::paper()};
}

inline Task<void> paper_pipeline(Simulator& sim, Host& host, std::vector<FileRef> files, double cpu_seconds,
                                 std::int64_t chunk, int pipeline, std::vector<PhaseRecord>& phases,
                                 std::vector<CacheRecord>* cache = nullptr) {
  auto snapshot = [&](int task, const char* phase) {
    if (cache == nullptr) return;
    for (std::size_t f = 0; f < files.size(); ++f) {
      cache->push_back({task, phase, static_cast<int>(f) + 1, host.cached(files[f])});
    }
  };
  for (int task = 1; task <= 3; ++task) {
    const IoResult read = co_await host.read_file(files[static_cast<std::size_t>(task - 1)], chunk);
    phases.push_back({pipeline, task, "read", read.start, read.end});
    snapshot(task, "read");
    const double compute_start = sim.now();
    co_await host.compute(cpu_seconds);
    phases.push_back({pipeline, task, "compute", compute_start, sim.now()});
    const IoResult write = co_await host.write_file(files[static_cast<std::size_t>(task)], chunk);
    phases.push_back({pipeline, task, "write", write.start, write.end});
    snapshot(task, "write");
    host.release_memory(read.bytes);
  }
}

}  // namespace pagecache::testing
