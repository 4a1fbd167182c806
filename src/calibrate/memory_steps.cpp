// calibrate's steps that measure memory and the page cache, one thread and every core.
#include "calibrate/steps.hpp"

#include "calibrate/measure.hpp"
#include "calibrate/reclaim.hpp"
#include "calibrate/text.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <thread>

namespace pagecache::calibrate {

namespace {

std::string cache_write_how(std::int64_t chunk) {
  return fmt::format("write() into the page cache, one thread, {} requests, not synced", size_text(chunk));
}

// With free page reporting, memory freed a moment ago is still backed by the host and memory
// free for longer is not (the kernel reports free blocks about 2 s after they are freed): waits
// until the kernel's count of reported memory has stopped growing (from 2.5 s, at most 6 s; 2.5 s
// where it is not counted), so that what follows takes memory the host has taken back.
void settle(const SystemInfo& s) {
  if (!s.free_page_reporting) return;
  const auto started = std::chrono::steady_clock::now();
  const auto waited = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count(); };
  std::int64_t before = reported_free_bytes();
  std::this_thread::sleep_for(std::chrono::milliseconds(2500));
  while (before >= 0 && waited() < 6.0 && !stop_requested()) {
    const std::int64_t now = reported_free_bytes();
    if (now == before) break;
    before = now;
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
  }
}

}  // namespace

// The measurements the memory steps and the NUMA step share (steps.hpp).

void write_cached(const Session& s, const std::filesystem::path& file) {
  cache_write(file, s.budget.cache_file, s.budget.chunk, Deadline(s.budget.memory_seconds * 8));
  sync_file(file);  // clean, and still cached: the reads read it
}

std::int64_t touch_bytes(const SystemInfo& sys) { return std::min(GiB, sys.memory_available / 8); }

Figure first_touch_figure(const Session& s, std::int64_t bytes) {
  const SystemInfo& sys = s.sys;
  first_touch(bytes, sys.page_size, Deadline(s.budget.memory_seconds * 4));  // warm-up
  return repeated(s.budget.repeat, [&](int) { return first_touch(bytes, sys.page_size, Deadline(s.budget.memory_seconds)); },
                  fmt::format("one byte written per {}-byte page of new anonymous memory just freed, one thread (transparent huge pages: {})",
                              sys.page_size, sys.transparent_hugepages.empty() ? "absent" : sys.transparent_hugepages));
}

std::int64_t copy_bytes(const Options& options) { return options.quick ? 32 * MiB : 256 * MiB; }

Figure copy_figure(const Session& s, int repeat, const std::function<void()>& source, const std::function<void()>& destination) {
  const std::int64_t bytes = copy_bytes(s.options);
  return repeated(
      repeat,
      [&](int) {
        if (source) source();
        return memory_copy(bytes, Deadline(s.budget.memory_seconds), destination);
      },
      fmt::format("memcpy of {}, one thread", size_text(bytes)));
}

Figure cached_reads_figure(const Session& s, const std::filesystem::path& cached, int threads) {
  const auto read_once = [&](int) { return cached_read(cached, s.budget.chunk, false, Deadline(s.budget.memory_seconds)); };
  return repeated(s.budget.repeat, [&](int) { return in_threads(threads, read_once); },
                  fmt::format("read() of cached data into reused buffers, {} threads at once", threads));
}

// Writes into free memory take memory just freed, as a task reusing what its own or others'
// work freed does (here's real runs: 1.9 GB into the cache at 2.6 GB/s), so each repetition is
// preceded by the free of the same amount (the first by an untimed warm-up).
void measure_cache_write(Calibration& c, Session& s, const std::filesystem::path& cached) {
  const std::int64_t cache_file = s.budget.cache_file;
  const std::int64_t chunk = s.budget.chunk;
  const double memory_seconds = s.budget.memory_seconds;
  s.next("page cache: write into free memory");
  const auto write_dropped = [&](const std::string& name, const Deadline& deadline) {
    const std::filesystem::path file = s.scratch.file(name);
    const Rate r = cache_write(file, cache_file, chunk, deadline);
    sync_and_drop(file);
    s.scratch.remove(file);
    return r;
  };
  write_dropped("warm-up", Deadline(memory_seconds * 8));
  c.memory_write = repeated(s.budget.repeat, [&](int i) { return write_dropped(fmt::format("write-{}", i), Deadline(memory_seconds * 4)); },
                            cache_write_how(chunk) + ", into memory just freed");
  write_cached(s, cached);
}

void measure_cached_reads(Calibration& c, Session& s, const std::filesystem::path& cached) {
  const std::int64_t chunk = s.budget.chunk;
  const double memory_seconds = s.budget.memory_seconds;
  s.next("page cache: cached reads");
  c.memory_read = repeated(s.budget.repeat, [&](int) { return cached_read(cached, chunk, false, Deadline(memory_seconds)); },
                           fmt::format("read() of cached data into a reused {} buffer, one thread", size_text(chunk)));
  c.memory_read_fresh = repeated(kOnce, [&](int) { return cached_read(cached, chunk, true, Deadline(memory_seconds)); },
                                 "read() of cached data into new memory, one thread");
}

void measure_first_touch(Calibration& c, Session& s) {
  s.next("memory: first touch");
  c.first_touch = first_touch_figure(s, touch_bytes(s.sys));
}

void measure_copies(Calibration& c, Session& s) {
  const double memory_seconds = s.budget.memory_seconds;
  s.next("memory: copies, one thread and every core");
  const std::int64_t copy = copy_bytes(s.options);
  c.copy_one = copy_figure(s, kOnce);
  c.copy_all = repeated(kOnce, [&](int) { return in_threads(s.sys.cores, [&](int) { return memory_copy(copy / 2, Deadline(memory_seconds)); }); },
                        fmt::format("memcpy of {} per thread, {} threads at once", size_text(copy / 2), s.sys.cores));
}

void measure_every_core(Calibration& c, Session& s, const std::filesystem::path& cached) {
  const SystemInfo& sys = s.sys;
  const std::int64_t chunk = s.budget.chunk;
  const double memory_seconds = s.budget.memory_seconds;
  s.next("page cache: every core at once");
  c.memory_aggregate_read = cached_reads_figure(s, cached, sys.cores);
  const std::int64_t share = std::max<std::int64_t>(chunk, s.budget.cache_file / sys.cores / chunk * chunk);
  const auto write_together = [&](const std::string& name) {
    std::vector<std::filesystem::path> written;
    for (int t = 0; t < sys.cores; ++t) written.push_back(s.scratch.file(fmt::format("{}-{}", name, t)));
    const Rate r = concurrently(written, [&](const std::filesystem::path& f) { return cache_write(f, share, chunk, Deadline(memory_seconds * 4)); });
    for (const auto& f : written) {
      sync_and_drop(f);
      s.scratch.remove(f);
    }
    return r;
  };
  write_together("together-warm-up");
  c.memory_aggregate_write = repeated(s.budget.repeat, [&](int i) { return write_together(fmt::format("together-{}", i)); },
                                      fmt::format("write() into the page cache with memory just freed, {} threads at once", sys.cores));
}

// With free page reporting, memory free for longer has gone back to the host and must be
// faulted in again. One wait for the kernel to report what was freed, then the buffered read
// and the writes, none freeing memory before the last (each write synced, kept cached), so
// that every one takes memory the host took back.
void measure_cold_memory(Calibration& c, Session& s, const std::filesystem::path& one) {
  const BufferedReading reading = buffered_reading(c);
  s.next("page cache: read and write into memory the host took back");
  settle(s.sys);
  c.buffered_read_cold =
      figure(buffered_read_cold(one, reading.request, Deadline(s.budget.disk_seconds)), reading.how + ", into memory the host took back");
  std::vector<std::filesystem::path> kept;
  c.memory_write_cold = repeated(
      s.budget.repeat,
      [&](int i) {
        kept.push_back(s.scratch.file(fmt::format("cold-{}", i)));
        const Rate r = cache_write(kept.back(), s.budget.cache_file, s.budget.chunk, Deadline(s.budget.memory_seconds * 4));
        sync_file(kept.back());
        return r;
      },
      cache_write_how(s.budget.chunk) + ", into memory free long enough for the host to take it back (free page reporting; one wait, then each)");
  for (const auto& f : kept) {
    sync_and_drop(f);
    s.scratch.remove(f);
  }
  sync_and_drop(one);
  s.scratch.remove(one);
}

// Not with --quick, nor in a memory cgroup with a limit (holding memory there could end in the
// group's OOM killer).
void measure_reclaimed_write(Calibration& c, Session& s) {
  if (s.options.quick) {
    c.memory_reclaimed_write = Figure{0.0, "not measured with --quick", false};
  } else if (s.sys.memory_limited) {
    c.memory_reclaimed_write = Figure{0.0, "not measured: this process is in a memory cgroup with a limit", false};
    c.notes.push_back("in a memory cgroup with a limit: the write into reclaimed pages was not measured");
  } else {
    s.next("page cache: write while reclaiming clean cache");
    // Whatever is left of 165 s: with the write-cache measurement's minute after it, calibrate
    // stays under four minutes.
    const double left = 165.0 - s.elapsed();
    c.memory_reclaimed_write =
        reclaimed_write(c, s.scratch, ReclaimSetting{std::min<std::int64_t>(c.size, 512 * MiB), s.budget.chunk, s.budget.need, std::max(0.0, left)});
  }
}

}  // namespace pagecache::calibrate
