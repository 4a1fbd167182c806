#pragma once
// IoController: turns chunked file reads and writes into page-cache changes and timed
// transfers: it carries out the plans of paper Algorithms 2 and 3 (a chunk read's steps in
// chunk_read.hpp, the plans in plan.hpp; docs/model.md §4).
//
// Every step reads the cache state as it is when the step runs; other processes may change
// it while this one waits for a transfer. The cache bookkeeping of a chunk (new blocks,
// re-accesses, application memory) is done when the chunk starts, before its transfers, so
// that the memory a chunk needs is taken from `free` at once and concurrent readers cannot
// count on it too.

#include "cache/dirty_throttle.hpp"
#include "cache/file_table.hpp"
#include "cache/flusher.hpp"
#include "cache/free_page_reporting.hpp"
#include "cache/page_cache.hpp"
#include "cache/plan.hpp"
#include "storage/readahead.hpp"

#include <pagecache/devices.hpp>
#include <pagecache/event.hpp>
#include <pagecache/host.hpp>
#include <pagecache/simulator.hpp>

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace pagecache::cache {

/// What one chunk or one whole-file operation moved, and from where.
struct IoTally {
  std::int64_t bytes = 0;
  std::int64_t cache_bytes = 0;  ///< served by (read) or written to (write) the page cache
  std::int64_t disk_bytes = 0;   ///< read from or written through to the device
  IoTally& operator+=(const IoTally& other) {
    bytes += other.bytes;
    cache_bytes += other.cache_bytes;
    disk_bytes += other.disk_bytes;
    return *this;
  }
};

/// `part` of `whole` as a fraction (0 for nothing).
inline double share(std::int64_t part, std::int64_t whole) {
  return whole > 0 ? static_cast<double>(part) / static_cast<double>(whole) : 0.0;
}

/// A whole file's read or write as Host reports it: its span and what it moved.
inline IoResult file_result(double start, double end, const IoTally& t) {
  return IoResult{.start = start, .end = end, .bytes = t.bytes, .cache_bytes = t.cache_bytes, .disk_bytes = t.disk_bytes};
}

class IoController {
 public:
  IoController(Simulator& sim, PageCache& cache, const Memory& memory, FileTable& files, Flusher& flusher);
  /// The memory of the host's NUMA node `node` (> 0), as its threads copy (Memory::set_numa).
  void set_node_memory(NodeId node, const Memory& memory) noexcept { memories_[node] = &memory, numa_ = true; }

  /// Writes `chunk` bytes to `file` (Algorithm 3 in writeback mode; disk then cache in
  /// writethrough mode).
  /// `at`: where the chunk goes in a file held by range (ReadRequest::kWholeFile: a chunk of a
  /// whole-file write, new data after what is cached).
  /// `node`: the writing thread's NUMA node (its new pages are taken there first).
  Task<IoTally> write_chunk(FileId file, std::int64_t chunk, std::int64_t at = ReadRequest::kWholeFile, NodeId node = 0);
  /// Reads a whole file in chunks of `chunk_size` bytes (Algorithm 2 per chunk; each chunk's
  /// copy stays in application memory until released); `direct`: bypassing the page cache
  /// (O_DIRECT: from the disk into the application's buffer).
  /// Its result is Host::read_file's: Host hands this task out as its own, so that a file read
  /// costs no frame of Host's. Not a coroutine itself: it checks the request (ConfigError at the
  /// call) and hands out the read.
  /// `group`: the reader's memory group, charged with its buffers (and with the new cache data
  /// if the file is the group's, PageCache::charge_file).
  /// `node`: the reading thread's NUMA node (PageCache::touch_from).
  Task<IoResult> read_file(FileId file, std::int64_t chunk_size, bool direct = false, GroupId group = kRootGroup, NodeId node = 0);
  /// Writes `bytes` to `file` in chunks of `chunk_size` bytes; `direct`: straight to the disk.
  /// Not a coroutine itself: it checks the request as read_file does and hands out the task
  /// that writes the file (throttled or not).
  /// `group`: the writer's memory group, which the file is charged to if no group has it.
  Task<IoResult> write_file(FileId file, std::int64_t bytes, std::int64_t chunk_size, bool direct = false, GroupId group = kRootGroup,
                            NodeId node = 0);
  /// Reads parts of a local file, the requests `next` yields one after the other (ranges
  /// within the file), into one buffer of `buffer` bytes held meanwhile. Each request reads
  /// the pages it touches as a chunk of read_file does (Algorithm 2 on its range: the cached
  /// parts re-accessed, the holes from the device, one device request each), sequential ones
  /// read ahead (RangeReadahead).
  /// From its start the file's page cache is held by range (PageCache::track_ranges).
  /// Throws ConfigError at the call for a remote file or a buffer <= 0, SimulationError from
  /// the task for a request outside the file or when the read cannot proceed.
  /// `direct`: O_DIRECT (Host::read_ranges).
  Task<IoResult> read_ranges(FileId file, std::function<bool(ByteRange&)> next, std::int64_t buffer, GroupId group = kRootGroup,
                             ReadAdvice advice = ReadAdvice::Normal, bool direct = false, NodeId node = 0);
  /// Writes parts of a local file, the requests `next` yields one after the other, each the
  /// pages it touches as a chunk of write_file (Algorithm 3, dirty throttling): holes become
  /// new dirty data, cached parts are written in place (PageCache::write_range). The file is
  /// held by range from its start. Errors as read_ranges'.
  Task<IoResult> write_ranges(FileId file, std::function<bool(ByteRange&)> next, GroupId group = kRootGroup, bool direct = false, NodeId node = 0);
  /// posix_fadvise(POSIX_FADV_WILLNEED): the holes of `range` of a local file are read into the
  /// page cache by a process of their own (the call returns at once), as readahead (untouched,
  /// at the inactive list's MRU end), one device request.
  void will_need(FileId file, ByteRange range);
  /// posix_fadvise(POSIX_FADV_DONTNEED): the clean data of `range` of a local file leaves the
  /// page cache now (PageCache::drop_clean_range). Returns the bytes dropped.
  std::int64_t dont_need(FileId file, ByteRange range);
  /// Takes `bytes` of application memory (a task's working memory), writing back and
  /// evicting cached data to make room. Throws SimulationError when nothing can free enough.
  Task<void> hold_memory(std::int64_t bytes, GroupId group = kRootGroup, NodeId node = 0);
  /// Makes `group` able to take `bytes` more (the kernel's try_charge): evicts the group's
  /// clean data, writes back its dirty data, waits for writebacks in flight. Throws
  /// SimulationError, with the time and the group, when nothing can free enough (the kernel
  /// would invoke the OOM killer in the group). Nothing to do for the root group.
  Task<void> make_group_room(GroupId group, std::int64_t bytes, FileId subject, const char* verb);
  /// fsync: writes back every dirty byte of `file` and waits for it, and for writebacks of it
  /// already in progress.
  Task<void> fsync(FileId file);
  /// Deletes the file's cached data (dirty data is discarded, never written), once its
  /// writebacks in progress have ended.
  Task<void> drop(FileId file);

  /// Serving another host (this one is an NFS server): sends `bytes` of `file` over `link`,
  /// from this host's page cache or, for what is not cached, from its disk (then cached).
  /// `client_copy` is the client's side of the transfer (its copy into its own page cache):
  /// each part is one flow through the source device, the link and the client's memory.
  /// `cursor`: where the client's read of the file left off in this host's cache (each page
  /// once per read, PageCache::reaccess), updated; nullptr: a read of its own.
  Task<void> serve_read(FileId file, std::int64_t bytes, const Route& route, FlowSpec client_copy, ReadCursor* cursor = nullptr);
  /// Receives `bytes` of `file` over `link` and writes them as this host's cache mode says
  /// (writethrough: to disk, then cached clean; writeback: into the cache, dirty).
  Task<void> serve_write(FileId file, std::int64_t bytes, const Route& route);

  /// The machine as it starts, before any run (memory in use set, files cached): the dirty
  /// throttling limit is the dirty threshold of that state (DirtyLimit::reset).
  void machine_at_rest();
  /// From now on, free memory the host took back (FreePageReporting) makes writes and first
  /// touches into it slower (Memory's cold_fault): `warm` bytes of the free memory were freed
  /// just before, the rest is cold. Call once the machine is at rest (files cached).
  void report_free_pages(double delay, std::int64_t warm);
  /// Caches `bytes` of `file` clean before the run starts: memory neither freed nor taken by
  /// the run (free page reporting does not see it).
  void cache_at_start(FileId file, std::int64_t bytes);

  /// Bytes written to devices to make room or to respect the dirty ratio (not counting the
  /// periodic flusher's).
  std::int64_t flushed_bytes() const noexcept { return flushed_; }
  /// Seconds each request of read_ranges and write_ranges takes besides its transfers
  /// (HostSpec::request_time).
  void set_request_time(double seconds) noexcept { request_time_ = seconds; }
  /// Chunks of the reads and writes of applications started on this host so far.
  std::uint64_t chunk_operations() const noexcept { return chunks_; }

 private:
  /// Throws ConfigError for a chunk size <= 0.
  void check_request(std::int64_t chunk_size) const;
  /// Reads `bytes` of a remote file from its server into this host's fresh memory;
  /// `server_cursor` as serve_read's.
  Task<void> serve_remote(FileId file, std::int64_t bytes, ReadCursor* server_cursor, NodeId node);
  /// serve_read's parts: `bytes` from this host's disk, or from its cache, to the client.
  Task<void> send_from_disk(const Route& route, const FileInfo& info, const FlowSpec& client_copy, std::int64_t bytes) const;
  Task<void> send_from_cache(const Route& route, const FlowSpec& client_copy, std::int64_t bytes) const;
  /// serve_write's in writethrough mode: `bytes` over the route to this host's disk.
  Task<void> send_to_disk(const Route& route, const FileInfo& info, std::int64_t bytes) const;
  /// read_ranges once checked.
  Task<IoResult> read_ranges_of(FileId file, std::function<bool(ByteRange&)> next, std::int64_t buffer, GroupId group, ReadAdvice advice, NodeId node);
  Task<IoResult> write_ranges_of(FileId file, std::function<bool(ByteRange&)> next, GroupId group, NodeId node);
  /// read_ranges and write_ranges with O_DIRECT, once checked: the device alone, request by
  /// request (a write then drops the clean cached data of its pages).
  Task<IoResult> ranges_direct(FileId file, std::function<bool(ByteRange&)> next, std::int64_t buffer, GroupId group, bool writing, NodeId node);
  /// will_need's process.
  Task<void> prefetch(FileId file, ByteRange range);
  /// A local file's read (read_file).
  Task<IoResult> read_whole_file(FileId file, std::int64_t chunk_size, bool direct, GroupId group, NodeId node);
  /// A remote file's read (read_file): from this host's cache and the server.
  Task<IoResult> read_remote_file(FileId file, std::int64_t chunk_size, bool direct, GroupId group, NodeId node);
  /// Takes `bytes` of application memory for `group` (a task's memory, an O_DIRECT read's
  /// buffer), making room in the group and in the host; errors name `verb` and `subject`.
  Task<void> take_buffer(std::int64_t bytes, GroupId group, FileId subject, const char* verb, NodeId node);
  /// Flushes up to `amount` dirty bytes (skipping `excluded`) and waits for their writes.
  Task<std::int64_t> write_back(std::int64_t amount, FileId excluded, FlushCause cause, GroupId group = kAnyGroup);
  /// A writer short of `bytes` of memory, with nothing to flush or evict, waits for copies and
  /// writebacks in flight; with none, nothing will ever free memory: throws SimulationError.
  void check_writer_can_wait(FileId file, std::int64_t bytes) const;
  Task<IoTally> write_chunk_writeback(FileId file, std::int64_t chunk, std::int64_t at = ReadRequest::kWholeFile, NodeId node = 0);
  /// Whether writeback-mode writers are paced (dirty throttling) rather than made to flush.
  bool throttles_writers() const noexcept;
  /// `bytes` of a file written in chunks in writeback mode under dirty throttling
  /// (CacheSettings::dirty_throttling).
  /// `whole_file`: a file's write (write_file), marking the file as being written meanwhile.
  /// `at`: where the bytes go in a file held by range, as write_chunk's.
  Task<IoResult> write_file_throttled(FileId file, std::int64_t bytes, std::int64_t chunk_size, bool whole_file, std::int64_t at, NodeId node);
  /// write_file chunk by chunk (not throttled), or straight to the disk.
  Task<IoResult> write_file_in_chunks(FileId file, std::int64_t bytes, std::int64_t chunk_size, bool direct, NodeId node);
  /// Copies `bytes` into the cache: the memory transfer, then a new dirty block; `reclaimed`:
  /// how many of its pages the writer evicted clean data for (Memory::write).
  /// Returns the bytes copied: all of them, unless the file's memory group had to make room
  /// and others took the memory meanwhile.
  Task<std::int64_t> write_to_cache(FileId file, std::int64_t bytes, std::int64_t reclaimed, std::int64_t at, NodeId node);
  /// A copy of `bytes` into the cache is done: new dirty data, at `at` in a file held by range.
  void commit_write(FileId file, std::int64_t at, std::int64_t bytes);
  Task<IoTally> write_chunk_writethrough(FileId file, std::int64_t chunk, std::int64_t at, NodeId node);
  /// A chunk of a remote file: to its server (write_chunk).
  Task<IoTally> write_chunk_remote(FileId file, std::int64_t chunk);
  /// A chunk of a client's read of a remote file; `cursor` and `server_cursor`: where the read
  /// left off in this host's cache and in the server's, updated.
  Task<IoTally> read_chunk_remote(FileId file, std::int64_t chunk, ReadCursor& cursor, ReadCursor& server_cursor, GroupId group, NodeId node);
  /// Makes room for `required` bytes (flush, then evict), sparing `spared`; if that is not
  /// enough while other transfers still hold memory (writebacks, copies in flight), waits for
  /// them and tries again. Throws SimulationError when nothing can ever free enough, naming
  /// what `verb` (e.g. "reading") was being done to `subject` (kNoFile: `verb` names what needs it).
  Task<void> make_room(std::int64_t required, FileId spared, FileId subject, const char* verb);
  /// Room for a chunk read (chunk_read.hpp, step 3) that eviction alone did not make, or for
  /// any chunk read of a reader in a memory group: room in the group for its `buffer` and the
  /// new cache data it is charged with, then in the host, until both hold at once. Returns
  /// the part of the chunk to read from the device. A coroutine only for these: most chunk
  /// reads need no more than evict_for_chunk, and a chunk read is the most frequent operation.
  /// Errors name `verb` (e.g. "reading") and the file.
  /// `offset`: as ReadRequest's.
  Task<std::int64_t> room_for_chunk(FileId file, std::int64_t file_size, std::int64_t bytes, std::int64_t buffer, std::int64_t offset, GroupId group,
                                    const char* verb);
  /// Waits until memory held by transfers in flight may have been released.
  Task<void> wait_for_progress();
  /// A write back's vectors: the parts it takes and its writes per device.
  struct FlushScratch {
    std::vector<PageCache::Flushed> parts;
    std::vector<std::pair<const Disk*, std::int64_t>> writes;
  };
  /// Spare vectors (emptied, their capacity kept) if any, else new ones; each write back hands
  /// its own back (release_scratch) once its writes end, so that writers flushing in step reuse
  /// vectors rather than make and free two per write back.
  FlushScratch take_scratch();
  void release_scratch(FlushScratch&& scratch);

  /// The memory as a thread on `node` copies: its node's.
  const Memory& memory(NodeId node) const noexcept { return *memories_[node]; }
  /// What a chunk read's transfers need: the share of its new pages the host took back, the
  /// bound of its device read into new cache pages and the buffer, where its cached data's
  /// copy is.
  struct ChunkCopies {
    double cold_share = 0.0;
    double bound = kUnbounded;
    RemoteShare remote;  // of the cached part's copy
  };
  /// A chunk read's steps between making its room and its transfers (start_chunk from the
  /// reader's node), and what its transfers need. Not a coroutine: what it reads of the
  /// tallies stays out of the reader's frame (10^5 readers).
  ChunkCopies start_read_chunk(const ReadRequest& request, std::int64_t disk_read, ReadCursor& cursor, GroupId group, NodeId node,
                               storage::Readahead* readahead, const Disk& disk);
  /// The share of `bytes` placed on other nodes than the toucher's since the tally's `what`
  /// was `before`, as a destination share.
  RemoteShare remote_since(std::int64_t RemoteTally::*what, std::int64_t before, std::int64_t bytes) const noexcept;

  Simulator* sim_;
  PageCache* cache_;
  std::array<const Memory*, kMaxNodes> memories_{};  // by node; one-node hosts: the first
  bool numa_ = false;                                 // several nodes: copies priced by where their pages are
  FileTable* files_;
  Flusher* flusher_;
  std::int64_t flushed_ = 0;
  std::uint64_t chunks_ = 0;
  double request_time_ = 0.0;
  DirtyThrottle throttle_;
  std::vector<FlushScratch> spare_scratch_;  // at most one per write back in flight
  std::optional<Event> progress_;
  std::optional<FreePageReporting> reporting_;  // none: no memory is ever cold
  /// Bytes taken from cold memory so far (FreePageReporting::cold_taken).
  std::int64_t cold_taken() const noexcept { return reporting_ ? reporting_->cold_taken() : 0; }
};

}  // namespace pagecache::cache
