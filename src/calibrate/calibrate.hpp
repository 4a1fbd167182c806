#pragma once
// `pcsim calibrate`: measures this machine's device and memory on the file system of a folder,
// reads the kernel's settings, and writes a platform file whose every value names the
// measurement it came from. Bounded in time (each measurement stops at its deadline) and in
// disk space (refused up front if the folder's file system has too little room); removes
// every file it made, also when interrupted.

#include "calibrate/cold_memory.hpp"
#include "calibrate/figure.hpp"
#include "calibrate/numa_figures.hpp"
#include "calibrate/request_latency.hpp"
#include "calibrate/system_info.hpp"
#include "calibrate/write_cache.hpp"

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace pagecache::calibrate {

struct Options {
  std::filesystem::path dir;
  /// Small files and short measurements (under 20 s), no measurement of reclaim nor of memory a
  /// VM's host took back, a short write-cache run whose figures are a comment only.
  bool quick = false;
  /// Bytes per measuring file (one per stream); 0: 1 GiB, or 64 MiB with `quick`.
  std::int64_t size = 0;
  /// Concurrent streams for the aggregate rates; 0: 4, or 2 with `quick`.
  int streams = 0;
  /// Repetitions of each measurement (the median is taken); 0: 3, or 1 with `quick`.
  int repeat = 0;
  /// Told before each step: its name, its number (from 1) and how many there are.
  std::function<void(const std::string& step, int number, int steps)> progress;
};

struct Calibration {
  SystemInfo system;
  std::string date;  ///< UTC, ISO 8601
  std::int64_t size = 0;
  int streams = 0;
  std::int64_t request = 0;
  bool quick = false;
  // The device (the platform's disk): reads with O_DIRECT; writes as writeback drains dirty
  // pages (what applications writing through the page cache get), O_DIRECT's for comparison.
  Figure disk_read, disk_aggregate_read;
  Figure writeback, aggregate_writeback;
  Figure disk_write, disk_aggregate_write;  ///< O_DIRECT, for comparison
  std::vector<RequestRate> request_rates;   ///< O_DIRECT reads by request size, the largest read_bw's
  RequestFit request_fit;
  WriteCache write_cache;                   ///< O_DIRECT writes until a write cache fills
  // Buffered reads of a file dropped from the cache, into memory just freed and into memory a
  // VM's host took back: for comparison, not in the platform.
  Figure buffered_read, buffered_read_cold;
  // Memory and the page cache.
  Figure memory_read;          ///< cached data into a reused buffer, one thread
  Figure memory_read_fresh;    ///< cached data into new memory, one thread
  Figure memory_write;         ///< into the page cache, memory just freed, one thread
  Figure memory_write_cold;    ///< the same, memory a VM's host took back
  ColdFault cold_fault;        ///< what touching memory the host took back costs beyond memory_write
  Figure memory_reclaimed_write;  ///< into the page cache, reclaiming clean cache, one thread
  Figure memory_aggregate_read, memory_aggregate_write;  ///< every core at once
  Figure first_touch;          ///< new anonymous memory, one thread
  Figure copy_one, copy_all;   ///< memcpy, for comparison
  /// The nodes, and the memory figures with the other node's memory over their own's.
  NumaFigures numa;
  /// The machine before measuring (a moment of doing nothing) and while measuring.
  Activity before, during;
  /// What could not be measured or may mislead, for the user.
  std::vector<std::string> notes;
  double seconds = 0.0;
};

/// Measures. Throws ConfigError for a folder that is not a writable directory or whose file
/// system has too little room; std::runtime_error if interrupted (after removing its files).
Calibration calibrate(const Options& options);

/// The platform file: one host with one disk, each value commented with its measurement.
std::string platform_toml(const Calibration& c);

}  // namespace pagecache::calibrate
