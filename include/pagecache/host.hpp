#pragma once
// Host: one machine of a simulated platform — cores, memory with its page cache, disks — and
// the operations applications run on it: chunked file reads and writes through the page
// cache, computation, and the release of application memory.
//
// Sizes are bytes, times seconds, bandwidths bytes per second. A Host owns its devices and
// its page cache (the paper's Memory Manager), its I/O Controller and its periodic flusher;
// it must be created after, and destroyed before, the Simulator and FairShare it uses.
//
//   pagecache::Simulator sim;
//   pagecache::FairShare share(sim);
//   pagecache::Host host(sim, share, {.memory = 268'000'000'000, ...});
//   auto disk = host.add_disk("sda", 465e6, 465e6);
//   auto input = host.add_file("file_1", 20'000'000'000, disk);
//   // in a process:  co_await host.read_file(input, 100'000'000);

#include <pagecache/cache_settings.hpp>
#include <pagecache/devices.hpp>
#include <pagecache/fair_share.hpp>
#include <pagecache/memory_state.hpp>
#include <pagecache/simulator.hpp>
#include <pagecache/task.hpp>

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

namespace pagecache {

struct HostSpec {
  std::string name = "host";
  int cores = 1;
  std::int64_t memory = 0;  ///< bytes of RAM
  MemoryBandwidth memory_bandwidth;
  CacheSettings cache;
  /// Memory held from the start and never released (e.g. tmpfs), counted as anonymous.
  std::int64_t memory_in_use = 0;
  /// With memory_bandwidth.cold_fault: seconds from a free to the host taking the memory back
  /// (the kernel's PAGE_REPORTING_DELAY), and the bytes of the free memory at the start that
  /// were freed just before it (a dropped cache); the rest of it is cold.
  double page_reporting_delay = 2.0;
  std::int64_t memory_freed_at_start = 0;
  /// Seconds a thread spends on each request of a read or write of parts of a file
  /// (read_ranges, write_ranges) besides its transfers: the system call and the page cache's
  /// look-up. 0: none.
  double request_time = 0.0;
  NumaSpec numa{};
};

/// A disk of a host (index in the order of add_disk).
struct DiskRef {
  std::uint32_t index = 0;
};
/// A memory group of a host (add_memory_group); the default, 0, is no group (the root).
struct GroupRef {
  std::uint16_t index = 0;
  /// The most groups a host can have (add_memory_group throws ConfigError beyond).
  static constexpr std::size_t kMax = 65534;
};
/// A NUMA node of a host (HostSpec::numa), by index.
struct NodeRef {
  std::uint8_t index = 0;
};
/// Who does an operation: the memory group charged with its memory, and the NUMA node its
/// thread runs on. A GroupRef alone is that group's thread on node 0.
struct Thread {
  GroupRef group;
  NodeRef node;
  Thread(GroupRef g = {}, NodeRef n = {}) : group(g), node(n) {}  // NOLINT(google-explicit-constructor): a group is a thread of it
};

/// A file known to a host (index in the order of add_file).
struct FileRef {
  std::uint32_t index = 0;
  friend bool operator==(FileRef, FileRef) = default;
};

/// A part of a file: `length` bytes from `offset`.
struct ByteRange {
  std::int64_t offset = 0;
  std::int64_t length = 0;
  friend bool operator==(const ByteRange&, const ByteRange&) = default;
};

/// posix_fadvise advice for a read of parts of a file (Host::read_ranges).
enum class ReadAdvice : std::uint8_t {
  Normal,      ///< the kernel's readahead for sequential requests
  Sequential,  ///< POSIX_FADV_SEQUENTIAL: readahead windows up to twice as large
  Random,      ///< POSIX_FADV_RANDOM: no readahead
};

/// What an I/O phase moved and when.
struct IoResult {
  double start = 0.0;
  double end = 0.0;
  std::int64_t bytes = 0;
  std::int64_t cache_bytes = 0;  ///< read from, or written into, the page cache
  std::int64_t disk_bytes = 0;   ///< read from, or written through to, the disk
};

class Host {
 public:
  Host(Simulator& sim, FairShare& share, HostSpec spec);
  ~Host();
  Host(const Host&) = delete;
  Host& operator=(const Host&) = delete;

  const std::string& name() const noexcept;
  const CacheSettings& cache_settings() const noexcept;

  DiskRef add_disk(std::string name, double read_bw, double write_bw, std::int64_t capacity = 0);
  /// A disk whose streams together may go faster than one.
  DiskRef add_disk(std::string name, DiskBandwidth bandwidth, std::int64_t capacity = 0);
  const Disk& disk(DiskRef disk) const;
  /// A file of `size` bytes on `disk`; `cached_at_start` puts it in the page cache (clean,
  /// inactive) at time 0.
  FileRef add_file(std::string name, std::int64_t size, DiskRef disk, bool cached_at_start = false);
  /// A file of `server` (one of its files), reached from this host over `route`, as through an
  /// NFS mount: reads fill this host's cache from the server's cache or disk; writes go to the
  /// server (no client write cache), which handles them as its own cache mode says. The route
  /// must outlive the host.
  FileRef add_remote_file(Host& server, FileRef server_file, const Route& route);
  /// The same over one link.
  FileRef add_remote_file(Host& server, FileRef server_file, const Link& link);
  const std::string& file_name(FileRef file) const;
  std::int64_t file_size(FileRef file) const;
  std::size_t file_count() const noexcept;

  /// Reads the whole file in chunks of `chunk_size` bytes; each chunk's copy is kept in
  /// application memory until release_memory(). `direct`: O_DIRECT, bypassing this host's page
  /// cache (an NFS server still serves from, and fills, its own). Throws ConfigError at the
  /// call for a file unknown here or a chunk size <= 0; SimulationError from the task when the
  /// read cannot proceed.
  Task<IoResult> read_file(FileRef file, std::int64_t chunk_size, bool direct = false, Thread thread = {});
  /// Reads parts of a local file: the requests `next` yields (it fills its argument and
  /// returns true, or returns false when there are no more), one after the other, into a
  /// buffer of `buffer` bytes the read holds meanwhile and then releases. Each request reads
  /// the pages it touches: what is cached of them is a hit, the rest one device request. From
  /// its start the file's page cache is held by byte range: which parts are
  /// cached counts from then on (whole-file reads and writes only count how much). Throws
  /// ConfigError at the call for a remote file or a buffer <= 0; SimulationError from the
  /// task for a request not within the file or when the read cannot proceed.
  /// Sequential requests (each starting where the one before ended, the first at 0) are read
  /// ahead as the kernel does, in windows up to the disk's read_ahead, as `advice` allows;
  /// readahead pages go to the inactive list untouched. `direct`: O_DIRECT, each request one
  /// device request of its bytes, the page cache neither read nor filled (nor the advice used).
  Task<IoResult> read_ranges(FileRef file, std::function<bool(ByteRange&)> next, std::int64_t buffer, Thread thread = {},
                             ReadAdvice advice = ReadAdvice::Normal, bool direct = false);
  /// posix_fadvise(POSIX_FADV_WILLNEED) on `range` of a local file: what is not cached of its
  /// pages is read into the page cache in the background (the call returns at once), as
  /// readahead is: one device request, the pages untouched at the inactive list's MRU end.
  void will_need(FileRef file, ByteRange range);
  /// posix_fadvise(POSIX_FADV_DONTNEED) on `range` of a local file: the clean data of its pages
  /// leaves the page cache now. Dirty data stays (the kernel starts its writeback; here the
  /// flusher writes it as any other). Returns the bytes dropped.
  std::int64_t dont_need(FileRef file, ByteRange range);
  /// Writes parts of a local file: the requests `next` yields, one after the other. Each writes
  /// the pages it touches: where they are not cached, new dirty data (as write_file's chunks,
  /// under the same dirty throttling); where they are, in place (clean pages become dirty,
  /// dirty pages stay so). An append is a write past what was written before: the file's size
  /// is what it ends at. Errors as read_ranges'. `direct`: O_DIRECT, each request one device
  /// request of its bytes, after which the clean cached data of its pages is dropped (the
  /// kernel invalidates them; dirty data there stays, not modelled).
  Task<IoResult> write_ranges(FileRef file, std::function<bool(ByteRange&)> next, Thread thread = {}, bool direct = false);
  /// Writes the file's whole size in chunks of `chunk_size` bytes. A file held by range (see
  /// read_ranges) is written in place from its start. `direct`: O_DIRECT (on an
  /// NFS mount the same as without: there is no client write cache). Errors as read_file's.
  Task<IoResult> write_file(FileRef file, std::int64_t chunk_size, bool direct = false, Thread thread = {});
  /// fsync(2): returns when every dirty byte of the file is on its disk.
  Task<void> fsync(FileRef file);
  /// Deletes the file's data from the page cache (unlink): dirty data is discarded unwritten.
  Task<void> delete_file(FileRef file);
  /// Runs `core_seconds` of computation on one core's worth of the host's CPU at most.
  Task<void> compute(double core_seconds);
  /// Takes `bytes` of application memory (a task's working memory), writing back and evicting
  /// cached data to make room; give it back with release_memory(). SimulationError from the
  /// task when the host cannot free enough.
  Task<void> hold_memory(std::int64_t bytes, Thread thread = {});
  /// Frees application memory (a task's buffers at its end), of the group that held it; on
  /// a NUMA host, the thread's node's first (which pages of a buffer are where is not kept).
  void release_memory(std::int64_t bytes, Thread thread = {});

  /// A thread starting on this host (a task), placed as the kernel places a new task (fork
  /// balancing, find_idlest_group): on the node with the fewest threads running, the lowest
  /// of equals. Give it back with end_thread when it ends.
  Thread start_thread(GroupRef group = {});
  void end_thread(Thread thread);
  /// The host's NUMA nodes (1 without).
  int nodes() const noexcept;

  /// A memory group (a cgroup with memory.max = `max` bytes, as Slurm or Kubernetes give each
  /// job): the application memory of the reads, writes and hold_memory calls given it, and
  /// the page cache of the files it touches first (a whole file is charged to the first group
  /// that caches it; the kernel charges each page), may not exceed `max`. At the limit the
  /// group reclaims its own data, writing back its dirty data if it must, whatever the host's
  /// free memory (mm/memcontrol.c, try_charge); when nothing can free enough, the operation
  /// fails with a SimulationError naming the group and the time (the kernel's OOM kill).
  /// Writers of the group are throttled at its own dirty limits too (group_dirty_limits).
  /// Not yet modelled: memory.high's penalty sleep.
  /// `high`: memory.high (0: none): above it the group reclaims its own data at each charge
  /// but is never refused.
  GroupRef add_memory_group(std::int64_t max, std::int64_t high = 0);
  /// The group's memory now: its application memory and the cache charged to it.
  std::int64_t group_usage(GroupRef group) const;

  MemoryState memory() const noexcept;
  std::int64_t cached(FileRef file) const noexcept;
  std::int64_t dirty(FileRef file) const noexcept;
  /// Bytes written to disk to make room or keep the dirty ratio, and by the periodic flusher.
  std::int64_t forced_flush_bytes() const noexcept;
  std::int64_t periodic_flush_bytes() const noexcept;
  /// Bytes of clean cached data evicted to make room.
  std::int64_t evicted_bytes() const noexcept;
  /// The most dirty data the page cache has held at once so far.
  std::int64_t peak_dirty_bytes() const noexcept;
  /// Chunks read and written by applications on this host (read_file, write_file) so far.
  std::uint64_t chunk_operations() const noexcept;

  /// Calls `observer(now, memory())` after every change of the host's memory.
  void set_memory_observer(std::function<void(double, const MemoryState&)> observer);
  /// Reports the host's flushes, evictions and throttling pauses to `sink` (nullptr: to none),
  /// as host number `index` (TraceStart::hosts).
  void set_trace(TraceSink* sink, std::uint32_t index);
  /// Checks every page-cache invariant after each operation (tests, debugging). Slow.
  void set_checking(bool on);
  /// Checks every page-cache invariant now; throws InvariantError.
  void check_invariants() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pagecache
