#pragma once
// The measurements of `pcsim calibrate`, each a loop of real I/O or memory operations on this
// machine that stops at its size or its deadline, whichever comes first, and says how many
// bytes it moved in how long. Files are the caller's (it makes and removes them).

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <vector>

namespace pagecache::calibrate {

/// Bytes moved in seconds.
struct Rate {
  std::int64_t bytes = 0;
  double seconds = 0.0;
  double per_second() const noexcept { return seconds > 0.0 ? static_cast<double>(bytes) / seconds : 0.0; }
};

/// When a measurement stops: `seconds` after it was made, or as soon as the user interrupts.
class Deadline {
 public:
  explicit Deadline(double seconds) : end_(std::chrono::steady_clock::now() + std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(seconds))) {}
  bool passed() const;

 private:
  std::chrono::steady_clock::time_point end_;
};

/// SIGINT or SIGTERM arrived since install_stop_handlers(): every loop stops, the caller
/// removes its files and exits.
void install_stop_handlers();
bool stop_requested() noexcept;

/// The file system refuses O_DIRECT (tmpfs, some FUSE file systems).
struct DirectIoUnsupported : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// --- The device ------------------------------------------------------------------------------
/// Writes `file` (made anew) with O_DIRECT in requests of `request` bytes, up to `size`: the
/// device's sequential write rate, the page cache bypassed, as writeback sees it (the
/// fdatasync after it, which also flushes the device's own cache, is not timed).
Rate direct_write(const std::filesystem::path& file, std::int64_t size, std::int64_t request, const Deadline& deadline);
/// Reads `file` with O_DIRECT: the device's sequential read rate.
Rate direct_read(const std::filesystem::path& file, std::int64_t request, const Deadline& deadline);
/// Writes `file` through the page cache, then fsync, both timed: what a buffered writer that
/// waits for its data to be on the device gets.
Rate buffered_write_synced(const std::filesystem::path& file, std::int64_t size, std::int64_t request, const Deadline& deadline);
/// Writes each file (made anew, `size` bytes) through the page cache, untimed, then fsyncs
/// them all at once, one thread each, timed from the common start to the last end: the rate at
/// which the kernel writes dirty pages back to the device, as the flusher drains them (with
/// whatever write cache lies below the file system). `size` must stay under the background
/// dirty threshold, so that no writeback starts before the clock does.
Rate writeback(const std::vector<std::filesystem::path>& files, std::int64_t size, std::int64_t request);
/// Drops `file`'s clean pages (POSIX_FADV_DONTNEED, no root needed) and reads it through the
/// page cache: the device with the kernel's readahead.
Rate buffered_read_cold(const std::filesystem::path& file, std::int64_t request, const Deadline& deadline);
/// A file grown with O_DIRECT writes of data no device can compress or deduplicate (random,
/// every 4 KiB block stamped with its own number): what a device with a cache of its own takes
/// in before that cache fills, and after.
class DirectAppender {
 public:
  DirectAppender(const std::filesystem::path& file, std::int64_t request);
  ~DirectAppender();
  DirectAppender(const DirectAppender&) = delete;
  DirectAppender& operator=(const DirectAppender&) = delete;
  /// Appends `bytes` (whole requests), or less at the deadline or when the file system has no
  /// more room; timed alone.
  Rate append(std::int64_t bytes, const Deadline& deadline);
  /// The file system refused a write for want of room (ENOSPC, EDQUOT).
  bool full() const noexcept { return full_; }
  std::int64_t size() const noexcept { return size_; }

 private:
  std::filesystem::path file_;
  int fd_;
  std::int64_t request_;
  char* buffer_ = nullptr;
  std::int64_t size_ = 0;
  std::uint64_t stamp_ = 0;
  bool full_ = false;
};
/// Runs `one` on each file, all at once, one thread each: their bytes over the time from the
/// common start to the last end.
Rate concurrently(const std::vector<std::filesystem::path>& files, const std::function<Rate(const std::filesystem::path&)>& one);

// --- Memory and the page cache ---------------------------------------------------------------
/// Writes `file` (made anew) through the page cache from a buffer already touched, without
/// waiting for the device: the copy into cache pages, timed alone.
Rate cache_write(const std::filesystem::path& file, std::int64_t size, std::int64_t request, const Deadline& deadline);
/// fsync, then drop the file's pages from the cache (untimed housekeeping).
void sync_and_drop(const std::filesystem::path& file);
/// fsync alone: the file stays cached, clean.
void sync_file(const std::filesystem::path& file);
/// Reads `file`, which must be cached, `request` bytes at a time: into one buffer of
/// `request` bytes touched before (`fresh` false), or each request into new memory never
/// touched (`fresh` true: every page faulted in and zeroed by the kernel as the copy lands).
Rate cached_read(const std::filesystem::path& file, std::int64_t request, bool fresh, const Deadline& deadline);
/// memcpy between two touched buffers of `bytes` each, repeatedly, in one thread.
/// `before_destination`, if given, runs once the source is touched and before the destination
/// is allocated: the NUMA measurement places the two on different nodes with it.
Rate memory_copy(std::int64_t bytes, const Deadline& deadline, const std::function<void()>& before_destination = {});
/// Touches one byte per page of `bytes` of new anonymous memory: the page faults and zeroing
/// of first touch.
Rate first_touch(std::int64_t bytes, std::int64_t page_size, const Deadline& deadline);
/// Runs `one` in `threads` threads at once; their bytes over the time to the last end.
Rate in_threads(int threads, const std::function<Rate(int)>& one);

/// Anonymous memory held (touched) until destroyed: to leave a given amount of memory free.
class MemoryHold {
 public:
  explicit MemoryHold(std::int64_t page_size) : page_size_(page_size) {}
  ~MemoryHold();
  MemoryHold(const MemoryHold&) = delete;
  MemoryHold& operator=(const MemoryHold&) = delete;
  /// Takes and touches `bytes` more.
  void add(std::int64_t bytes);
  std::int64_t bytes() const noexcept { return held_; }

 private:
  std::int64_t page_size_;
  std::int64_t held_ = 0;
  std::vector<std::pair<void*, std::int64_t>> regions_;
};

}  // namespace pagecache::calibrate
