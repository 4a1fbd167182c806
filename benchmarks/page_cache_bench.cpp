// Page cache micro-benchmarks: the LRU list operations of PageCache (touch, split, evict,
// flush) with n blocks cached, and the chunk read and write paths of a Host (I/O controller,
// page cache, devices) on a warm cache. Figures are per operation; each list operation should
// cost O(1) or O(log n) whatever n (docs/model.md §2), so they should stay flat as n grows.
#include "cache/page_cache.hpp"

#include <pagecache/host.hpp>

#include <benchmark/benchmark.h>

#include <cstdint>
#include <random>
#include <vector>

namespace {

using pagecache::CacheSettings;
using pagecache::cache::FileId;
using pagecache::cache::PageCache;

constexpr std::int64_t kBlock = 1'000'000;

// A cache holding n clean blocks, one per file (so that no two merge), all inactive.
void fill_clean(PageCache& cache, std::int64_t n) {
  for (std::int64_t f = 0; f < n; ++f) cache.add_read(static_cast<FileId>(f), kBlock, 0.0);
}

// Touch: re-reading one file's data moves it to the active list (two touches with the kernel
// settings: the first marks it), and the lists are balanced.
void BM_LruTouch(benchmark::State& state) {
  const std::int64_t n = state.range(0);
  PageCache cache(4 * n * kBlock, CacheSettings::kernel());
  cache.set_checking(false);
  fill_clean(cache, n);
  std::mt19937_64 rng(1);
  std::uniform_int_distribution<std::int64_t> file(0, n - 1);
  double now = 1.0;
  for (auto _ : state) cache.reaccess(static_cast<FileId>(file(rng)), kBlock, now += 1e-6);
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
  // A block's size: one cache line (64 bytes) is what the lists' speed at 10^5 blocks assumes.
  state.counters["block_bytes"] = static_cast<double>(sizeof(pagecache::cache::Block));
}
BENCHMARK(BM_LruTouch)->RangeMultiplier(10)->Range(10, 100000);

// Split: reading a quarter of a file's block splits it and moves that part.
void BM_LruSplit(benchmark::State& state) {
  const std::int64_t n = state.range(0);
  PageCache cache(4 * n * kBlock, CacheSettings::paper());
  cache.set_checking(false);
  fill_clean(cache, n);
  std::mt19937_64 rng(2);
  std::uniform_int_distribution<std::int64_t> file(0, n - 1);
  double now = 1.0;
  std::int64_t splits = 0;
  for (auto _ : state) {
    const auto f = static_cast<FileId>(file(rng));
    if (cache.file(f).in(pagecache::cache::ListKind::Inactive) >= kBlock / 4) {
      cache.reaccess(f, kBlock / 4, now += 1e-6);
      ++splits;
    } else {
      state.PauseTiming();
      cache.drop_file(f);  // all read: start the file again, one inactive block
      cache.add_read(f, kBlock, now);
      state.ResumeTiming();
    }
  }
  state.SetItemsProcessed(splits);
}
BENCHMARK(BM_LruSplit)->RangeMultiplier(10)->Range(10, 100000);

// Evict: free half a block from the LRU end, then cache new data behind, with n blocks.
void BM_LruEvict(benchmark::State& state) {
  const std::int64_t n = state.range(0);
  PageCache cache(n * kBlock, CacheSettings::kernel());
  cache.set_checking(false);
  fill_clean(cache, n);
  FileId next = static_cast<FileId>(n);
  for (auto _ : state) {
    cache.evict(kBlock / 2, pagecache::cache::kNoFile);
    cache.add_read(next++, kBlock / 2, 0.0);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
}
BENCHMARK(BM_LruEvict)->RangeMultiplier(10)->Range(10, 100000);

// Flush: take the oldest dirty data for writeback and end the write, with n dirty blocks,
// then dirty a new block: the cache stays at n dirty blocks.
void BM_LruFlush(benchmark::State& state) {
  const std::int64_t n = state.range(0);
  PageCache cache(4 * n * kBlock, CacheSettings::kernel());
  cache.set_checking(false);
  double now = 0.0;
  for (std::int64_t f = 0; f < n; ++f) cache.add_dirty(static_cast<FileId>(f), kBlock, now += 1e-6);
  std::vector<PageCache::Flushed> taken;
  FileId next = static_cast<FileId>(n);
  for (auto _ : state) {
    taken.clear();
    cache.flush(kBlock, pagecache::cache::kNoFile, taken);
    for (const auto& t : taken) cache.end_writeback(t);
    cache.evict(kBlock, pagecache::cache::kNoFile);
    cache.add_dirty(next++, kBlock, now += 1e-6);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
}
BENCHMARK(BM_LruFlush)->RangeMultiplier(10)->Range(10, 100000);

// The chunk paths of a Host on a warm cache: one process reads a cached 10 GB file in 100 MB
// chunks (cache hits: a memory flow and the LRU updates per chunk), or writes one (new dirty
// data under the background threshold), over and over. Figure: per chunk.
pagecache::Task<void> reread(pagecache::Host& host, pagecache::FileRef file, int times) {
  for (int i = 0; i < times; ++i) {
    const pagecache::IoResult r = co_await host.read_file(file, 100'000'000);
    host.release_memory(r.bytes);
  }
}

pagecache::Task<void> rewrite(pagecache::Host& host, pagecache::FileRef file, int times) {
  for (int i = 0; i < times; ++i) {
    co_await host.write_file(file, 100'000'000);
    co_await host.delete_file(file);  // its dirty data is dropped: the cache stays warm and small
  }
}

template <class Process>
void run_chunks(benchmark::State& state, bool cached, Process process) {
  constexpr int kTimes = 100;  // 100 passes over 100 chunks: 10^4 chunk operations
  for (auto _ : state) {
    state.PauseTiming();
    pagecache::Simulator sim;
    pagecache::FairShare share(sim);
    pagecache::HostSpec spec{.name = "node",
                             .cores = 4,
                             .memory = 256'000'000'000,
                             .memory_bandwidth = {6860e6, 2764e6, 100e9, 50e9, 6.1e9},
                             .cache = CacheSettings::kernel()};
    pagecache::Host host(sim, share, spec);
    const auto file = host.add_file("data", 10'000'000'000, host.add_disk("ssd", 510e6, 516e6), cached);
    sim.spawn(process(host, file, kTimes));
    state.ResumeTiming();
    sim.run();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * kTimes * 100);
}

void BM_IoChunkReadWarm(benchmark::State& state) { run_chunks(state, true, reread); }
BENCHMARK(BM_IoChunkReadWarm)->Unit(benchmark::kMillisecond);

void BM_IoChunkWrite(benchmark::State& state) { run_chunks(state, false, rewrite); }
BENCHMARK(BM_IoChunkWrite)->Unit(benchmark::kMillisecond);

}  // namespace
