#pragma once
// The measuring steps of calibrate(), in the order it runs them, and what they share: the
// sizes and deadlines chosen for this machine, the scratch folder, the clock and the progress.

#include "calibrate/calibrate.hpp"
#include "calibrate/scratch.hpp"

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace pagecache::calibrate {

/// Figures for comparison only, not in the platform: one measurement keeps the time down.
inline constexpr int kOnce = 1;

/// The sizes, repetitions and deadlines of one calibration, chosen from the options and the machine.
struct Budget {
  int repeat = 1;               ///< repetitions of each platform figure
  double disk_seconds = 0.0;    ///< per repetition
  double memory_seconds = 0.0;  ///< per repetition
  bool cold = false;            ///< memory a VM's host took back is measured
  bool reclaim = false;         ///< the write into pages reclaimed from clean cache is measured
  std::int64_t need = 0;        ///< bytes the folder's file system must have free
  std::int64_t cache_file = 0;  ///< bytes of a page-cache measuring file
  std::int64_t chunk = 0;       ///< write() and read() request into and from the page cache
};

/// What every step is given.
struct Session {
  const Options& options;
  const SystemInfo& sys;
  const Budget& budget;
  const Scratch& scratch;
  std::chrono::steady_clock::time_point started;
  int step = 0;
  int steps = 0;

  /// Seconds since calibrate() began.
  double elapsed() const;
  /// Stops if the user asked to, then tells the user the step that begins.
  void next(const std::string& name);
};

/// Throws std::runtime_error if the user interrupted (the scratch folder goes with the stack).
void check_stopped();

/// The background dirty limit the kernel applies now, in bytes (of the memory available to the page cache).
std::int64_t background_limit(const SystemInfo& s);

/// The buffered read of a file dropped from the cache: its request and how it is measured.
struct BufferedReading {
  std::int64_t request = 0;
  std::string how;
};
BufferedReading buffered_reading(const Calibration& c);

// --- The device (device_steps.cpp) -----------------------------------------------------------
/// O_DIRECT reads and writes, one stream (`one`) then several at once (`many`); false if the
/// file system refuses O_DIRECT (then noted, and the steps skipped).
bool measure_streams(Calibration& c, Session& s, const std::filesystem::path& one, const std::vector<std::filesystem::path>& many);
/// Writeback of dirty data, one file and `many` at once.
void measure_writeback(Calibration& c, Session& s, const std::vector<std::filesystem::path>& many);
/// The buffered read of `one` into memory just freed; the device's read rates without O_DIRECT.
void measure_buffered_read(Calibration& c, Session& s, const std::filesystem::path& one, bool direct);
/// O_DIRECT writes until the device's own write cache fills.
void measure_device_write_cache(Calibration& c, Session& s, bool direct);

// --- Memory and the page cache (memory_steps.cpp) --------------------------------------------
// One measurement each, as the platform's memory figures are made; the NUMA step makes them
// again with the thread and its memory placed on nodes.
/// Writes `file` through the page cache and syncs it: it stays cached, clean, for the reads.
void write_cached(const Session& s, const std::filesystem::path& file);
/// Bytes of new anonymous memory memory_first_touch_bw is measured on.
std::int64_t touch_bytes(const SystemInfo& sys);
/// One thread touching `bytes` of new anonymous memory: an untimed warm-up, then the
/// budget's repetitions.
Figure first_touch_figure(const Session& s, std::int64_t bytes);
/// Bytes of each buffer of the one-thread copy.
std::int64_t copy_bytes(const Options& options);
/// One thread's memcpy, `repeat` times; before each, `source` runs before the source buffer is
/// allocated and `destination` before the destination is (either may be empty).
Figure copy_figure(const Session& s, int repeat, const std::function<void()>& source = {}, const std::function<void()>& destination = {});
/// `threads` threads at once reading `cached` into reused buffers of their own, the budget's
/// repetitions.
Figure cached_reads_figure(const Session& s, const std::filesystem::path& cached, int threads);

/// Writes into free memory, then writes `cached`, which stays cached (clean) for the reads.
void measure_cache_write(Calibration& c, Session& s, const std::filesystem::path& cached);
void measure_cached_reads(Calibration& c, Session& s, const std::filesystem::path& cached);
void measure_first_touch(Calibration& c, Session& s);
void measure_copies(Calibration& c, Session& s);
/// Reads of `cached` and writes into the page cache, every core at once.
void measure_every_core(Calibration& c, Session& s, const std::filesystem::path& cached);
/// The buffered read of `one` and writes into memory the host took back; removes `one`.
void measure_cold_memory(Calibration& c, Session& s, const std::filesystem::path& one);
/// The write into pages reclaimed from clean cache, or why it is not measured.
void measure_reclaimed_write(Calibration& c, Session& s);

}  // namespace pagecache::calibrate
