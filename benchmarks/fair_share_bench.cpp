// Fair share: N processes keep N flows running on one disk (or a disk and a link); each, when
// its flow finishes, starts another. The figure is the wall time per flow start+finish; with processor sharing
// it should grow like log N, not N.
#include <pagecache/devices.hpp>
#include <pagecache/fair_share.hpp>

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdint>
#include <memory>

namespace {

pagecache::Task<void> reader(const pagecache::Disk& disk, std::int64_t flows, std::int64_t seed) {
  std::uint64_t x = static_cast<std::uint64_t>(seed) * 2654435761u + 1;
  for (std::int64_t i = 0; i < flows; ++i) {
    x = x * 6364136223846793005ull + 1442695040888963407ull;  // sizes 1..100 MB
    co_await disk.read(static_cast<std::int64_t>(1'000'000 + (x >> 33) % 99'000'000));
  }
}

// N processes, each running `per_process` flows back to back on the device that
// `make_device(share)` builds; reports the wall time per flow start+finish.
template <class MakeDevice, class Process>
void run_concurrent_flows(benchmark::State& state, MakeDevice make_device, Process process) {
  const auto concurrent = state.range(0);
  // At least 2*10^5 flows per iteration and 20 per process, so that every N measures a long
  // steady state (each finish followed by a start) rather than the initial burst.
  const std::int64_t per_process = std::max<std::int64_t>(20, 200'000 / concurrent);
  std::int64_t flows = 0;
  for (auto _ : state) {
    state.PauseTiming();
    auto sim = std::make_unique<pagecache::Simulator>();
    auto share = std::make_unique<pagecache::FairShare>(*sim);
    const auto device = make_device(*share);
    for (std::int64_t p = 0; p < concurrent; ++p) sim->spawn(process(*device, per_process, p));
    state.ResumeTiming();
    sim->run();
    state.PauseTiming();  // teardown is not part of the figure
    share.reset();
    sim.reset();
    state.ResumeTiming();
    flows += concurrent * per_process;
  }
  state.SetItemsProcessed(flows);
  state.counters["time_per_flow"] =
      benchmark::Counter(static_cast<double>(flows), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_DiskConcurrentFlows(benchmark::State& state) {
  run_concurrent_flows(
      state, [](pagecache::FairShare& share) { return std::make_unique<pagecache::Disk>(share, "disk", 500e6, 400e6); },
      &reader);
}
BENCHMARK(BM_DiskConcurrentFlows)->RangeMultiplier(10)->Range(10, 100000)->Unit(benchmark::kMillisecond)->UseRealTime();

// The same with a per-flow bound that binds for part of the flows (memory copies under an
// aggregate limit): exercises the bounded group of processor sharing.
pagecache::Task<void> copier(const pagecache::Memory& memory, std::int64_t flows, std::int64_t seed) {
  std::uint64_t x = static_cast<std::uint64_t>(seed) * 2654435761u + 3;
  for (std::int64_t i = 0; i < flows; ++i) {
    x = x * 6364136223846793005ull + 1442695040888963407ull;
    const std::int64_t bytes = static_cast<std::int64_t>(1'000'000 + (x >> 33) % 99'000'000);
    if ((x >> 20) & 1) co_await memory.read(bytes);
    else co_await memory.write(bytes);
  }
}

void BM_MemoryConcurrentFlows(benchmark::State& state) {
  // Aggregate about 5 flows' worth: with more flows the aggregate binds.
  run_concurrent_flows(
      state,
      [](pagecache::FairShare& share) {
        return std::make_unique<pagecache::Memory>(share, "memory", pagecache::MemoryBandwidth{6.8e9, 2.7e9, 34e9, 14e9});
      },
      &copier);
}
BENCHMARK(BM_MemoryConcurrentFlows)->RangeMultiplier(10)->Range(10, 100000)->Unit(benchmark::kMillisecond)->UseRealTime();

// Flows that cross two resources (a read from a server's disk over a network link, as with
// NFS) are solved by progressive filling over their component, whose flows form classes of
// interchangeable flows: the cost per flow should not grow with N either.
struct ServerPath {
  explicit ServerPath(pagecache::FairShare& share) : disk(share, "disk", 500e6, 400e6), link(share, "link", 300e6, 0.0) {}
  pagecache::Disk disk;
  pagecache::Link link;
};

pagecache::Task<void> remote_reader(const ServerPath& path, std::int64_t flows, std::int64_t seed) {
  std::uint64_t x = static_cast<std::uint64_t>(seed) * 2654435761u + 5;
  for (std::int64_t i = 0; i < flows; ++i) {
    x = x * 6364136223846793005ull + 1442695040888963407ull;
    const auto bytes = static_cast<double>(1'000'000 + (x >> 33) % 99'000'000);
    co_await path.link.send_through(pagecache::FlowSpec{.work = bytes}.through(path.disk.read_usage()));
  }
}

void BM_CoupledConcurrentFlows(benchmark::State& state) {
  run_concurrent_flows(
      state, [](pagecache::FairShare& share) { return std::make_unique<ServerPath>(share); }, &remote_reader);
}
BENCHMARK(BM_CoupledConcurrentFlows)->RangeMultiplier(10)->Range(10, 100000)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
