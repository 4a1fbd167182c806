#include "calibrate/calibrate.hpp"

#include "calibrate/measure.hpp"
#include "calibrate/reclaim.hpp"
#include "calibrate/scratch.hpp"
#include "calibrate/text.hpp"
#include "calibrate/write_cache.hpp"

#include <pagecache/error.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <sstream>
#include <system_error>
#include <thread>

#include <unistd.h>

namespace pagecache::calibrate {

namespace {


std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  ::gmtime_r(&now, &tm);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return text;
}


void check_stopped() {
  if (stop_requested()) throw std::runtime_error("interrupted: the files made so far are removed");
}

// The dirty limits the kernel applies now, in bytes (of the memory available to the page cache).
std::int64_t background_limit(const SystemInfo& s) {
  if (s.dirty_background_bytes > 0) return s.dirty_background_bytes;
  return static_cast<std::int64_t>(s.dirty_background_ratio * static_cast<double>(s.memory_available));
}

// What the machine did apart from calibrate, and what a hypervisor does with its memory.
std::vector<std::string> activity_notes(const Calibration& c) {
  std::vector<std::string> notes;
  const SystemInfo& s = c.system;
  if (c.before.others_busy_cores > 0.2) {
    notes.push_back(fmt::format("before measuring, other work kept {:.2f} of the {} cores busy: the figures share the machine with it",
                                c.before.others_busy_cores, s.cores));
  }
  if (c.during.others_busy_cores > 0.2) {
    notes.push_back(fmt::format("while measuring, {:.2f} cores were busy outside calibrate (other processes, or the kernel's own threads: "
                                "writeback, reclaim)",
                                c.during.others_busy_cores));
  }
  const double steal = std::max(c.before.steal_pct, c.during.steal_pct);
  if (steal > 2.0) {
    notes.push_back(fmt::format("the hypervisor took {:.1f} % of the CPUs' time (steal): other guests compete for its cores", steal));
  }
  if (s.hypervisor) {
    notes.push_back("a virtual machine: the device rates may be the host's cache rather than its disk, and speeds may change with what the "
                    "host does");
  }
  if (s.free_page_reporting) {
    std::string reported;
    if (c.during.reported > 0) reported = fmt::format(" ({} reported while measuring)", size_text(c.during.reported));
    std::string cold;
    if (c.memory_write_cold.measured && c.memory_write.measured) {
      cold = fmt::format(": a write into memory the host took back went at {}, into memory just freed at {} (memory_write_bw, what a task "
                         "reusing freed memory gets){}",
                         rate_text(c.memory_write_cold.value), rate_text(c.memory_write.value),
                         c.cold_fault.known ? "; memory_cold_fault_bw gives pcsim the difference" : "; pcsim has one rate for both");
    }
    notes.push_back(fmt::format("free page reporting is on (a virtio balloon): memory this machine frees goes back to the host{} a few seconds "
                                "later, and its next first touch waits for the host to give it again{}",
                                reported, cold));
  } else if (s.balloon_device) {
    notes.push_back("a virtio balloon: the host can take memory back while this runs");
  }
  if (c.during.memory_total_change != 0) {
    notes.push_back(fmt::format("MemTotal changed by {} MiB while measuring: a balloon took or gave memory", c.during.memory_total_change / MiB));
  }
  return notes;
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

Calibration calibrate(const Options& options) {
  const auto started = std::chrono::steady_clock::now();
  const auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count(); };
  std::error_code ec;
  if (!std::filesystem::is_directory(options.dir, ec)) throw ConfigError(fmt::format("--dir '{}': not a folder", options.dir.string()));
  if (::access(options.dir.c_str(), W_OK) != 0) throw ConfigError(fmt::format("--dir '{}': not writable by this user", options.dir.string()));

  Calibration c;
  c.system = read_system_info(options.dir);
  c.date = utc_now();
  c.quick = options.quick;
  c.size = options.size > 0 ? options.size : (options.quick ? 64 * MiB : GiB);
  c.streams = options.streams > 0 ? options.streams : (options.quick ? 2 : 4);
  c.request = std::min<std::int64_t>(options.quick ? 4 * MiB : 16 * MiB, c.size);
  c.size = std::max(c.request, c.size / c.request * c.request);  // whole requests (O_DIRECT)
  const int repeat = options.repeat > 0 ? options.repeat : (options.quick ? 1 : 3);
  const int once = 1;  // figures for comparison only, not in the platform: one measurement keeps the time down
  const double disk_seconds = options.quick ? 0.6 : 1.5;  // per repetition
  const double memory_seconds = options.quick ? 0.3 : 0.6;
  const SystemInfo& sys = c.system;
  // Memory a VM's host took back: measured after a wait of seconds for the kernel to report it.
  const bool cold = sys.free_page_reporting && !options.quick;
  const bool reclaim = !options.quick && !sys.memory_limited;

  // Room: the single stream's file and the streams' files at once, plus the cache files. (The
  // write-cache measurement takes at most half of what is free when it begins, and says so.)
  const std::int64_t need = (1 + static_cast<std::int64_t>(c.streams)) * c.size + c.size;
  if (sys.file_system_free < need) {
    throw ConfigError(fmt::format("--dir '{}': its file system has {} free for this user; calibrate writes up to {} there (--size {} per file, "
                                  "{} streams; a smaller --size needs less)",
                                  options.dir.string(), size_text(sys.file_system_free), size_text(need), size_text(c.size), c.streams));
  }
  // Memory: the cache files and the fresh buffers must fit in what is available.
  // (At least 256 MiB, so that a copy at memory speed takes a measurable time.)
  const std::int64_t cache_file = std::max(16 * MiB, std::min(std::max(c.size, 256 * MiB), background_limit(sys) / 2));
  if (sys.memory_available < 5 * cache_file) {
    throw ConfigError(fmt::format("only {} of memory available: calibrate needs {} (a smaller --size needs less)", size_text(sys.memory_available),
                                  size_text(5 * cache_file)));
  }

  // What the machine does while this does nothing: other load, the hypervisor's steal.
  const ActivityMark idle;
  std::this_thread::sleep_for(std::chrono::milliseconds(options.quick ? 200 : 500));
  c.before = idle.since();
  const ActivityMark measuring;

  const Scratch scratch(options.dir, "pcsim-calibrate");
  const int steps = 13 + (cold ? 1 : 0) + (reclaim ? 1 : 0);
  int step = 0;
  const auto next = [&](const std::string& name) {
    check_stopped();
    if (options.progress) options.progress(name, ++step, steps);
  };

  // --- The device: O_DIRECT, large requests; one stream, then several at once. The single
  // stream's file stays until the buffered reads into memory the host took back.
  const std::filesystem::path one = scratch.file("stream-0");
  std::vector<std::filesystem::path> many;
  for (int i = 1; i <= c.streams; ++i) many.push_back(scratch.file(fmt::format("stream-{}", i)));
  bool direct = true;
  try {
    next("device: write, one stream");
    c.disk_write = repeated(once, [&](int) { return direct_write(one, c.size, c.request, Deadline(disk_seconds)); },
                            fmt::format("O_DIRECT sequential write, one stream, {} requests (the fdatasync after it not timed)", size_text(c.request)));
    next("device: read, one stream");
    c.disk_read = repeated(repeat, [&](int) { return direct_read(one, c.request, Deadline(disk_seconds)); },
                           fmt::format("O_DIRECT sequential read, one stream, {} requests", size_text(c.request)));
    next("device: read, one stream, by request size");
    for (const std::int64_t size : {MiB / 16, MiB / 4, MiB, 4 * MiB, 16 * MiB}) {
      if (size >= c.request) break;
      c.request_rates.push_back(RequestRate{size, repeated(repeat, [&](int) { return direct_read(one, size, Deadline(disk_seconds)); }, "")});
    }
    c.request_rates.push_back(RequestRate{c.request, c.disk_read});
    c.request_fit = fit_request_latency(c.request_rates);
    next(fmt::format("device: write, {} streams", c.streams));
    c.disk_aggregate_write = repeated(
        once,
        [&](int) {
          const Deadline together(disk_seconds);
          return concurrently(many, [&](const std::filesystem::path& f) { return direct_write(f, c.size, c.request, together); });
        },
        fmt::format("O_DIRECT sequential writes, {} streams at once", c.streams));
    next(fmt::format("device: read, {} streams", c.streams));
    c.disk_aggregate_read = repeated(
        repeat,
        [&](int) {
          const Deadline together(disk_seconds);
          return concurrently(many, [&](const std::filesystem::path& f) { return direct_read(f, c.request, together); });
        },
        fmt::format("O_DIRECT sequential reads, {} streams at once", c.streams));
  } catch (const DirectIoUnsupported& e) {
    direct = false;
    c.notes.push_back(fmt::format("{}: the device is measured through the page cache instead (buffered, synced or dropped)", e.what()));
    c.request_rates.clear();
    c.request_fit = RequestFit{};
    c.request_fit.why = "the file system refuses O_DIRECT";
    step = 5;
  }
  for (const auto& f : many) scratch.remove(f);
  check_stopped();
  // --- Writeback: dirty data written, then synced. Under half the background threshold (no
  // writeback before the clock starts) and about what the O_DIRECT write did in a second (a
  // slow disk is not given minutes of work).
  next(fmt::format("device: writeback, one file and {} at once", c.streams));
  const std::filesystem::path synced = scratch.file("writeback");
  std::int64_t dirty = std::min(c.size, background_limit(sys) / 2);
  if (c.disk_write.measured) dirty = std::min(dirty, static_cast<std::int64_t>(c.disk_write.value));  // about a second's
  dirty = std::max(c.request, dirty / c.request * c.request);
  const std::int64_t dirty_each = std::max(c.request, dirty / c.streams / c.request * c.request);
  c.writeback = repeated(
      repeat,
      [&](int) {
        const Rate r = writeback({synced}, dirty, c.request);
        scratch.remove(synced);
        return r;
      },
      fmt::format("writeback: fsync of {} just written through the page cache (the write not timed), one file", size_text(dirty)));
  c.aggregate_writeback = repeated(
      repeat,
      [&](int) {
        const Rate r = writeback(many, dirty_each, c.request);
        for (const auto& f : many) scratch.remove(f);
        return r;
      },
      fmt::format("writeback: {} files of {} just written, fsync of each at once", c.streams, size_text(dirty_each)));

  // Buffered reads: each page of the cache the read fills is memory just freed (as much freed
  // right before, after the writeback files' pages), as a task reading after others' work freed
  // memory gets.
  next("device: buffered read, for comparison");
  if (!direct) buffered_write_synced(one, c.size, c.request, Deadline(disk_seconds));
  const std::int64_t buffered_request = std::min(MiB, c.request);
  const std::string buffered_how = fmt::format("buffered read (read(), {} requests, kernel readahead) of a file dropped from the cache "
                                               "(POSIX_FADV_DONTNEED)",
                                               size_text(buffered_request));
  {
    MemoryHold freed(sys.page_size);
    freed.add(c.size);
  }
  c.buffered_read = figure(buffered_read_cold(one, buffered_request, Deadline(disk_seconds)), buffered_how + ", into memory just freed");
  sync_and_drop(one);
  if (!cold) scratch.remove(one);
  if (!direct) {
    c.disk_read = c.buffered_read;
    c.disk_aggregate_read = c.disk_read;
  }

  // --- Memory and the page cache. The cache file is under half the background dirty
  // threshold, so that writing it is a copy into free pages, not throttled.
  // Writes into free memory and first touches take memory just freed, as a task reusing what
  // its own or others' work freed does (here's real runs: 1.9 GB into the cache at 2.6 GB/s),
  // so each repetition is preceded by the free of the same amount (the first by an untimed
  // warm-up).
  const std::filesystem::path cached = scratch.file("cached");
  const std::int64_t chunk = std::min<std::int64_t>(64 * MiB, cache_file);
  next("page cache: write into free memory");
  const auto write_dropped = [&](const std::string& name, const Deadline& deadline) {
    const std::filesystem::path file = scratch.file(name);
    const Rate r = cache_write(file, cache_file, chunk, deadline);
    sync_and_drop(file);
    scratch.remove(file);
    return r;
  };
  write_dropped("warm-up", Deadline(memory_seconds * 8));
  const std::string write_how = fmt::format("write() into the page cache, one thread, {} requests, not synced", size_text(chunk));
  c.memory_write = repeated(repeat, [&](int i) { return write_dropped(fmt::format("write-{}", i), Deadline(memory_seconds * 4)); },
                            write_how + ", into memory just freed");
  cache_write(cached, cache_file, chunk, Deadline(memory_seconds * 8));
  sync_file(cached);  // clean, and still cached: the reads below read it
  next("page cache: cached reads");
  c.memory_read = repeated(repeat, [&](int) { return cached_read(cached, chunk, false, Deadline(memory_seconds)); },
                           fmt::format("read() of cached data into a reused {} buffer, one thread", size_text(chunk)));
  c.memory_read_fresh = repeated(once, [&](int) { return cached_read(cached, chunk, true, Deadline(memory_seconds)); },
                                 "read() of cached data into new memory, one thread");
  next("memory: first touch");
  const std::int64_t touch = std::min(GiB, sys.memory_available / 8);
  first_touch(touch, sys.page_size, Deadline(memory_seconds * 4));  // warm-up
  c.first_touch = repeated(repeat, [&](int) { return first_touch(touch, sys.page_size, Deadline(memory_seconds)); },
                           fmt::format("one byte written per {}-byte page of new anonymous memory just freed, one thread (transparent huge pages: {})",
                                       sys.page_size, sys.transparent_hugepages.empty() ? "absent" : sys.transparent_hugepages));
  next("memory: copies, one thread and every core");
  const std::int64_t copy = options.quick ? 32 * MiB : 256 * MiB;
  c.copy_one = repeated(once, [&](int) { return memory_copy(copy, Deadline(memory_seconds)); }, fmt::format("memcpy of {}, one thread", size_text(copy)));
  c.copy_all = repeated(once, [&](int) { return in_threads(sys.cores, [&](int) { return memory_copy(copy / 2, Deadline(memory_seconds)); }); },
                        fmt::format("memcpy of {} per thread, {} threads at once", size_text(copy / 2), sys.cores));
  next("page cache: every core at once");
  c.memory_aggregate_read = repeated(
      repeat, [&](int) { return in_threads(sys.cores, [&](int) { return cached_read(cached, chunk, false, Deadline(memory_seconds)); }); },
      fmt::format("read() of cached data into reused buffers, {} threads at once", sys.cores));
  const std::int64_t share = std::max<std::int64_t>(chunk, cache_file / sys.cores / chunk * chunk);
  const auto write_together = [&](const std::string& name) {
    std::vector<std::filesystem::path> written;
    for (int t = 0; t < sys.cores; ++t) written.push_back(scratch.file(fmt::format("{}-{}", name, t)));
    const Rate r = concurrently(written, [&](const std::filesystem::path& f) { return cache_write(f, share, chunk, Deadline(memory_seconds * 4)); });
    for (const auto& f : written) {
      sync_and_drop(f);
      scratch.remove(f);
    }
    return r;
  };
  write_together("together-warm-up");
  c.memory_aggregate_write = repeated(repeat, [&](int i) { return write_together(fmt::format("together-{}", i)); },
                                      fmt::format("write() into the page cache with memory just freed, {} threads at once", sys.cores));
  sync_and_drop(cached);
  scratch.remove(cached);

  // --- With free page reporting, memory free for longer has gone back to the host and must be
  // faulted in again. One wait for the kernel to report what was freed, then the buffered read
  // and the writes, none freeing memory before the last (each write synced, kept cached), so
  // that every one takes memory the host took back.
  if (cold) {
    next("page cache: read and write into memory the host took back");
    settle(sys);
    c.buffered_read_cold =
        figure(buffered_read_cold(one, buffered_request, Deadline(disk_seconds)), buffered_how + ", into memory the host took back");
    std::vector<std::filesystem::path> kept;
    c.memory_write_cold = repeated(
        repeat,
        [&](int i) {
          kept.push_back(scratch.file(fmt::format("cold-{}", i)));
          const Rate r = cache_write(kept.back(), cache_file, chunk, Deadline(memory_seconds * 4));
          sync_file(kept.back());
          return r;
        },
        write_how + ", into memory free long enough for the host to take it back (free page reporting; one wait, then each)");
    for (const auto& f : kept) {
      sync_and_drop(f);
      scratch.remove(f);
    }
    sync_and_drop(one);
    scratch.remove(one);
  }
  c.cold_fault = cold_fault_rate(sys.free_page_reporting, c.memory_write, c.memory_write_cold);
  if (sys.free_page_reporting && options.quick) c.cold_fault.why = "not measured with --quick";

  // --- Writing into pages reclaimed from clean cache (reclaim.hpp). Not with --quick, nor in
  // a memory cgroup with a limit (holding memory there could end in the group's OOM killer).
  if (options.quick) {
    c.memory_reclaimed_write = Figure{0.0, "not measured with --quick", false};
  } else if (sys.memory_limited) {
    c.memory_reclaimed_write = Figure{0.0, "not measured: this process is in a memory cgroup with a limit", false};
    c.notes.push_back("in a memory cgroup with a limit: the write into reclaimed pages was not measured");
  } else {
    next("page cache: write while reclaiming clean cache");
    // Whatever is left of 165 s: with the write-cache measurement's minute after it, calibrate
    // stays under four minutes.
    const double left = 165.0 - elapsed();
    c.memory_reclaimed_write = reclaimed_write(c, scratch, ReclaimSetting{std::min<std::int64_t>(c.size, 512 * MiB), chunk, need, std::max(0.0, left)});
  }

  // --- The device's own write cache: last, as what it writes may keep a host's or a
  // controller's cache busy for a while after.
  next("device: write until a write cache fills");
  if (!direct) {
    c.write_cache.why = "the file system refuses O_DIRECT";
  } else {
    WriteCacheSetting w;
    w.request = c.request;
    w.quick = options.quick;
    if (options.quick) {
      // A check that the measurement works, not a measurement.
      w.piece = std::max(c.request, c.size / 4 / c.request * c.request);
      w.most = 16 * w.piece;
      w.seconds = 2.0;
    } else {
      w.piece = std::max(c.request, 256 * MiB / c.request * c.request);
      w.most = 64 * GiB;
      w.seconds = std::clamp(225.0 - elapsed(), 15.0, 60.0);  // about a minute, within the four
    }
    c.write_cache = measure_write_cache(options.dir, scratch, w);
  }
  check_stopped();

  c.during = measuring.since();

  // What makes these figures less than they seem.
  for (const auto& [key, f] : {std::pair<const char*, const Figure*>{"read_bw", &c.disk_read}, {"write_bw", &c.writeback},
                               {"aggregate_read_bw", &c.disk_aggregate_read}, {"aggregate_write_bw", &c.aggregate_writeback},
                               {"memory_read_bw", &c.memory_read}, {"memory_write_bw", &c.memory_write},
                               {"memory_aggregate_read_bw", &c.memory_aggregate_read}, {"memory_aggregate_write_bw", &c.memory_aggregate_write},
                               {"memory_first_touch_bw", &c.first_touch}}) {
    if (f->measured && f->spread_pct > 20.0) {
      c.notes.push_back(fmt::format("{} varied by {:.0f} % between its measurements: a noisy machine (other load), or memory or a device whose "
                                    "speed depends on its history (a virtual machine's host); pcsim takes the median",
                                    key, f->spread_pct));
    }
  }
  for (std::string& note : activity_notes(c)) c.notes.push_back(std::move(note));
  if (!sys.root) {
    c.notes.push_back("not root: the whole page cache could not be dropped; each measuring file was dropped by itself (POSIX_FADV_DONTNEED), "
                      "which needs no root");
  }
  if (c.disk_read.measured && c.disk_read.value > 8e9) {
    c.notes.push_back(fmt::format("the device read at {}: faster than most disks; a cache below the file system may have served it",
                                  rate_text(c.disk_read.value)));
  }
  if (c.writeback.measured && c.disk_write.measured && c.writeback.value > 1.25 * c.disk_write.value) {
    c.notes.push_back(fmt::format("writeback drained at {}, O_DIRECT writes went at {}: a write cache below the file system (a virtual "
                                  "machine's host, a controller) absorbs written data; write_bw is writeback's, which applications writing "
                                  "through the page cache get while that cache has room",
                                  rate_text(c.writeback.value), rate_text(c.disk_write.value)));
  }
  if (c.write_cache.measured && !c.write_cache.setting.quick && c.writeback.measured) {
    const WriteCacheFinding& f = c.write_cache.finding;
    const bool above = c.writeback.value > f.sustained;
    if (f.fell) {
      c.notes.push_back(fmt::format("write_bw (writeback, {}) is {} sustained_write_bw ({}), the device's rate once its write cache is full "
                                    "(after {} of O_DIRECT writes){}",
                                    rate_text(c.writeback.value), above ? "above" : "not above", rate_text(f.sustained),
                                    size_text(f.cache_bytes), above ? ": writing back more than that cache holds goes slower than write_bw" : ""));
    } else {
      std::int64_t bytes = 0;
      for (const Rate& r : c.write_cache.pieces) bytes += r.bytes;
      c.notes.push_back(fmt::format("write_bw (writeback, {}) is {} the rate O_DIRECT writes sustained over {} ({}, no write cache found)",
                                    rate_text(c.writeback.value), above ? "above" : "not above", size_text(bytes), rate_text(f.sustained)));
    }
  }
  c.seconds = elapsed();
  return c;
}

std::string platform_toml(const Calibration& c) {
  const SystemInfo& s = c.system;
  std::string out = fmt::format("# Measured by `pcsim calibrate` on {} ({:.0f} s{}).\n", c.date, c.seconds, c.quick ? ", --quick: rough" : "");
  out += fmt::format("# Machine: {}, {} {}, {} cores, {} of memory, Linux {}{}.\n", s.hostname, s.cpu_model.empty() ? "CPU" : s.cpu_model,
                     s.hypervisor ? "(virtual machine)" : "", s.cores, size_text(s.memory_total), s.kernel, s.root ? "" : ", not root");
  out += fmt::format("# Device: the file system of the folder measured in ({}), files of {}, {} streams at once.\n", s.file_system, size_text(c.size),
                     c.streams);
  out += fmt::format("# Other activity: {:.2f} cores busy outside calibrate before it measured, {:.2f} while it measured; steal {:.1f} % and "
                     "{:.1f} %{}.\n",
                     c.before.others_busy_cores, c.during.others_busy_cores, c.before.steal_pct, c.during.steal_pct,
                     c.during.reported >= 0 ? fmt::format("; {} of free memory reported to the host while measuring", size_text(c.during.reported)) : "");
  for (const std::string& note : c.notes) out += fmt::format("# Note: {}\n", note);
  const auto rate = [](const char* key, const Figure& f) {
    if (!f.measured) return fmt::format("# {} not set: {}\n", key, f.how);
    return fmt::format("# {}\n{} = \"{}\"\n", f.how, key, rate_text(f.value));
  };
  out += fmt::format("\n[[hosts]]\nname = \"{}\"\n", s.hostname);
  out += fmt::format("# processors online\ncores = {}\n", s.cores);
  out += fmt::format("# /proc/meminfo MemTotal\nmemory = \"{} MiB\"\n", s.memory_total / MiB);
  out += fmt::format("# MemTotal - MemAvailable when measured: what the page cache could not have\nmemory_in_use = \"{} MiB\"\n",
                     (s.memory_total - s.memory_available) / MiB);
  out += rate("memory_read_bw", c.memory_read);
  out += rate("memory_write_bw", c.memory_write);
  out += rate("memory_aggregate_read_bw", c.memory_aggregate_read);
  out += rate("memory_aggregate_write_bw", c.memory_aggregate_write);
  out += rate("memory_first_touch_bw", c.first_touch);
  out += rate("memory_reclaimed_write_bw", c.memory_reclaimed_write);
  out += cold_fault_toml(c.cold_fault, c.memory_write, c.memory_write_cold);
  if (c.memory_write_cold.measured) out += fmt::format("# for comparison: {}: {}\n", c.memory_write_cold.how, rate_text(c.memory_write_cold.value));
  if (c.memory_read_fresh.measured) out += fmt::format("# for comparison: {}: {}\n", c.memory_read_fresh.how, rate_text(c.memory_read_fresh.value));
  if (c.copy_one.measured) out += fmt::format("# for comparison: {}: {}\n", c.copy_one.how, rate_text(c.copy_one.value));
  if (c.copy_all.measured) out += fmt::format("# for comparison: {}: {}\n", c.copy_all.how, rate_text(c.copy_all.value));

  out += "\n[hosts.page_cache]\n";
  if (s.dirty_bytes > 0 || s.dirty_background_bytes > 0) {
    out += fmt::format("# /proc/sys/vm/dirty_bytes {} and dirty_background_bytes {}: as fractions of MemTotal\n", s.dirty_bytes,
                       s.dirty_background_bytes);
  } else {
    out += "# /proc/sys/vm/dirty_ratio and dirty_background_ratio\n";
  }
  const double total = static_cast<double>(std::max<std::int64_t>(s.memory_total, 1));
  const double ratio = s.dirty_bytes > 0 ? static_cast<double>(s.dirty_bytes) / total : s.dirty_ratio;
  const double background = s.dirty_background_bytes > 0 ? static_cast<double>(s.dirty_background_bytes) / total : s.dirty_background_ratio;
  out += fmt::format("dirty_ratio = {:.4g}\ndirty_background_ratio = {:.4g}\n", ratio, background);
  out += fmt::format("# dirty_expire_centisecs, dirty_writeback_centisecs\ndirty_expire = \"{:g} s\"\nwriteback_interval = \"{:g} s\"\n", s.dirty_expire,
                     s.writeback_interval);

  out += "\n[[hosts.disks]]\nname = \"disk\"\n";
  out += rate("read_bw", c.disk_read);
  out += rate("write_bw", c.writeback);
  // Streams together no faster than one (a disk that serves one stream at a time, or noise):
  // pcsim takes the aggregate as one stream's, which it may not be below.
  const auto aggregate = [&](const char* key, const Figure& together, const Figure& one) {
    if (!together.measured || !one.measured || together.value >= one.value) return rate(key, together);
    Figure taken = one;
    taken.how = fmt::format("{}: {}, under one stream's; taken as one stream's", together.how, rate_text(together.value));
    return rate(key, taken);
  };
  out += aggregate("aggregate_read_bw", c.disk_aggregate_read, c.disk_read);
  out += aggregate("aggregate_write_bw", c.aggregate_writeback, c.writeback);
  out += request_latency_toml(c.request_rates, c.request_fit, c.size);
  const DeviceLimits& d = s.device;
  const std::string device = d.device.empty() ? "" : fmt::format(" ({})", d.device);
  if (d.read_ahead < 0) {
    out += fmt::format("# read_ahead not set: {}\n", d.read_ahead_from);
  } else {
    out += fmt::format("# the kernel's readahead window for this file system, read, not measured: {}{}\nread_ahead = \"{} KiB\"\n", d.read_ahead_from,
                       device, d.read_ahead / 1024);
  }
  if (d.max_request < 0) {
    out += fmt::format("# max_request not set: {}\n", d.max_request_from);
  } else {
    out += fmt::format("# the largest request the block layer sends the device, read, not measured: {}{}\nmax_request = \"{} KiB\"\n",
                       d.max_request_from, device, d.max_request / 1024);
  }
  out += write_cache_toml(c.write_cache, c.writeback.measured ? c.writeback.value : 0.0);
  for (const Figure* f : {&c.buffered_read, &c.buffered_read_cold, &c.disk_write, &c.disk_aggregate_write}) {
    if (f->measured) out += fmt::format("# for comparison: {}: {}\n", f->how, rate_text(f->value));
  }
  return out;
}

}  // namespace pagecache::calibrate
