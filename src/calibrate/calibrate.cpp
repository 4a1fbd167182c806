#include "calibrate/calibrate.hpp"

#include "calibrate/measure.hpp"
#include "calibrate/node_binding.hpp"
#include "calibrate/notes.hpp"
#include "calibrate/numa_steps.hpp"
#include "calibrate/scratch.hpp"
#include "calibrate/steps.hpp"
#include "calibrate/text.hpp"

#include <pagecache/error.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <ctime>
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

void check_folder(const std::filesystem::path& dir) {
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) throw ConfigError(fmt::format("--dir '{}': not a folder", dir.string()));
  if (::access(dir.c_str(), W_OK) != 0) throw ConfigError(fmt::format("--dir '{}': not writable by this user", dir.string()));
}

void choose_sizes(Calibration& c, const Options& options) {
  c.quick = options.quick;
  c.size = options.size > 0 ? options.size : (options.quick ? 64 * MiB : GiB);
  c.streams = options.streams > 0 ? options.streams : (options.quick ? 2 : 4);
  c.request = std::min<std::int64_t>(options.quick ? 4 * MiB : 16 * MiB, c.size);
  c.size = std::max(c.request, c.size / c.request * c.request);  // whole requests (O_DIRECT)
}

Budget choose_budget(const Calibration& c, const Options& options) {
  const SystemInfo& sys = c.system;
  Budget b;
  b.repeat = options.repeat > 0 ? options.repeat : (options.quick ? 1 : 3);
  b.disk_seconds = options.quick ? 0.6 : 1.5;
  b.memory_seconds = options.quick ? 0.3 : 0.6;
  // Memory a VM's host took back: measured after a wait of seconds for the kernel to report it.
  b.cold = sys.free_page_reporting && !options.quick;
  b.reclaim = !options.quick && !sys.memory_limited;
  // Room: the single stream's file and the streams' files at once, plus the cache files. (The
  // write-cache measurement takes at most half of what is free when it begins, and says so.)
  b.need = (1 + static_cast<std::int64_t>(c.streams)) * c.size + c.size;
  // Memory: the cache files and the fresh buffers must fit in what is available.
  // (At least 256 MiB, so that a copy at memory speed takes a measurable time.)
  b.cache_file = std::max(16 * MiB, std::min(std::max(c.size, 256 * MiB), background_limit(sys) / 2));
  b.chunk = std::min<std::int64_t>(64 * MiB, b.cache_file);
  return b;
}

void check_room(const Calibration& c, const Options& options, const Budget& b) {
  const SystemInfo& sys = c.system;
  if (sys.file_system_free < b.need) {
    throw ConfigError(fmt::format("--dir '{}': its file system has {} free for this user; calibrate writes up to {} there (--size {} per file, "
                                  "{} streams; a smaller --size needs less)",
                                  options.dir.string(), size_text(sys.file_system_free), size_text(b.need), size_text(c.size), c.streams));
  }
  if (sys.memory_available < 5 * b.cache_file) {
    throw ConfigError(fmt::format("only {} of memory available: calibrate needs {} (a smaller --size needs less)", size_text(sys.memory_available),
                                  size_text(5 * b.cache_file)));
  }
}

// What the machine does while this does nothing: other load, the hypervisor's steal.
Activity idle_activity(bool quick) {
  const ActivityMark idle;
  std::this_thread::sleep_for(std::chrono::milliseconds(quick ? 200 : 500));
  return idle.since();
}

}  // namespace

void check_stopped() {
  if (stop_requested()) throw std::runtime_error("interrupted: the files made so far are removed");
}

std::int64_t background_limit(const SystemInfo& s) {
  if (s.dirty_background_bytes > 0) return s.dirty_background_bytes;
  return static_cast<std::int64_t>(s.dirty_background_ratio * static_cast<double>(s.memory_available));
}

double Session::elapsed() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count(); }

void Session::next(const std::string& name) {
  check_stopped();
  if (options.progress) options.progress(name, ++step, steps);
}

Calibration calibrate(const Options& options) {
  const auto started = std::chrono::steady_clock::now();
  check_folder(options.dir);
  Calibration c;
  c.system = read_system_info(options.dir);
  c.date = utc_now();
  c.numa.topology = read_numa_topology();  // before measuring: a malformed sysfs stops calibrate at once
  const int nodes = static_cast<int>(c.numa.topology.nodes.size());
  choose_sizes(c, options);
  const Budget budget = choose_budget(c, options);
  check_room(c, options, budget);

  c.before = idle_activity(options.quick);
  const ActivityMark measuring;
  const Scratch scratch(options.dir, "pcsim-calibrate");
  Session s{options, c.system, budget, scratch, started, 0, 13 + (budget.cold ? 1 : 0) + (budget.reclaim ? 1 : 0) + (nodes > 1 ? 1 : 0)};

  // --- The device: O_DIRECT, large requests; one stream, then several at once. The single
  // stream's file stays until the buffered reads into memory the host took back.
  const std::filesystem::path one = scratch.file("stream-0");
  std::vector<std::filesystem::path> many;
  for (int i = 1; i <= c.streams; ++i) many.push_back(scratch.file(fmt::format("stream-{}", i)));
  const bool direct = measure_streams(c, s, one, many);
  for (const auto& f : many) scratch.remove(f);
  check_stopped();
  measure_writeback(c, s, many);
  measure_buffered_read(c, s, one, direct);

  // --- Memory and the page cache. The cache file is under half the background dirty
  // threshold, so that writing it is a copy into free pages, not throttled.
  const std::filesystem::path cached = scratch.file("cached");
  measure_cache_write(c, s, cached);
  measure_cached_reads(c, s, cached);
  measure_first_touch(c, s);
  measure_copies(c, s);
  measure_every_core(c, s, cached);
  sync_and_drop(cached);
  scratch.remove(cached);
  SystemNodeBinding binding;
  measure_numa(c, s, binding, numa_probes(s, nodes));
  if (budget.cold) measure_cold_memory(c, s, one);
  c.cold_fault = cold_fault_rate(c.system.free_page_reporting, c.memory_write, c.memory_write_cold);
  if (c.system.free_page_reporting && options.quick) c.cold_fault.why = "not measured with --quick";
  measure_reclaimed_write(c, s);

  // --- The device's own write cache: last.
  measure_device_write_cache(c, s, direct);
  check_stopped();

  c.during = measuring.since();
  add_notes(c);
  c.seconds = s.elapsed();
  return c;
}

}  // namespace pagecache::calibrate
