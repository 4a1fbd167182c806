// Embedding pcsim: one host with one disk; an application reads a 20 GB file, computes for
// 28 s and writes a 20 GB result, twice in a row (the second time its input is in the page
// cache). Prints each phase's start, end and throughput, and the memory at the end.
//
// Build with the project (target `read_compute_write`), or against an installed pcsim:
//   find_package(pagecache)  +  target_link_libraries(app PRIVATE pagecache::pagecache)

#include <pagecache/host.hpp>

#include <cstdio>
#include <string>

namespace {

constexpr std::int64_t GB = 1'000'000'000;
constexpr std::int64_t kChunk = 100'000'000;  // the application reads and writes 100 MB at a time

void print_phase(const char* task, const char* phase, const pagecache::IoResult& r) {
  const double seconds = r.end - r.start;
  std::printf("%-6s %-8s %8.2f %8.2f %9.1f %8.1f %8.1f\n", task, phase, r.start, r.end,
              static_cast<double>(r.bytes) / 1e6 / seconds, static_cast<double>(r.cache_bytes) / 1e9,
              static_cast<double>(r.disk_bytes) / 1e9);
}

pagecache::Task<void> application(pagecache::Simulator& sim, pagecache::Host& host, pagecache::FileRef input,
                                  pagecache::FileRef output, pagecache::FileRef output2) {
  for (const auto& [name, out] : {std::pair{"task 1", output}, std::pair{"task 2", output2}}) {
    const pagecache::IoResult read = co_await host.read_file(input, kChunk);
    print_phase(name, "read", read);
    const double start = sim.now();
    co_await host.compute(28.0);
    std::printf("%-6s %-8s %8.2f %8.2f\n", name, "compute", start, sim.now());
    const pagecache::IoResult write = co_await host.write_file(out, kChunk);
    print_phase(name, "write", write);
    host.release_memory(read.bytes);  // the task's buffers are freed when it ends
  }
}

}  // namespace

int main() {
  pagecache::Simulator sim;
  pagecache::FairShare share(sim);
  // The paper's host as WRENCH-cache modelled it: 268 GB of memory behind one 4812 MB/s
  // channel, 32 cores, the paper's page cache settings.
  pagecache::Host host(sim, share,
                       {.name = "node",
                        .cores = 32,
                        .memory = 268 * GB,
                        .memory_bandwidth = pagecache::MemoryBandwidth::shared_channel(4812e6),
                        .cache = pagecache::CacheSettings::paper()});
  const pagecache::DiskRef disk = host.add_disk("ssd", 465e6, 465e6);
  const pagecache::FileRef input = host.add_file("input", 20 * GB, disk);
  const pagecache::FileRef output = host.add_file("output", 20 * GB, disk);
  const pagecache::FileRef output2 = host.add_file("output2", 20 * GB, disk);

  std::printf("%-6s %-8s %8s %8s %9s %8s %8s\n", "task", "phase", "start_s", "end_s", "MB/s", "cache_GB", "disk_GB");
  sim.spawn(application(sim, host, input, output, output2));
  sim.run();

  const pagecache::MemoryState m = host.memory();
  std::printf("\nend of simulation at %.2f s (dirty data written back by the flusher)\n", sim.now());
  std::printf("memory: %.1f GB cached, %.1f GB dirty, %.1f GB free of %.1f GB\n", static_cast<double>(m.cached) / 1e9,
              static_cast<double>(m.dirty) / 1e9, static_cast<double>(m.free) / 1e9, static_cast<double>(m.total) / 1e9);
  return 0;
}
