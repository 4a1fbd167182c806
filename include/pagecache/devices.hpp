#pragma once
// Devices: the hardware a host's I/O and computation go through, as fair-share resources
// (docs/model.md §5). Bandwidths are bytes per second, sizes bytes, latencies seconds.
//
//   Disk    one time-shared resource with separate read and write bandwidths: a read at rate r
//           uses r / aggregate_read of the disk, a write r / aggregate_write; one stream (one
//           transfer) goes at most at read / write (many devices serve several streams faster
//           than one; by default the two are equal). Optionally a request latency, which a
//           stream issuing one request at a time waits for, and a write cache in front of a
//           slower medium (DiskBandwidth).
//   Memory  an aggregate resource (what all cores together can move, read and write
//           bandwidths) plus a per-flow bound (what one thread can copy).
//   Link    a network link: bandwidth, plus a latency paid once per transfer; shared by its
//           flows, or a fatpipe (each flow may take the whole bandwidth, as SimGrid's FATPIPE).
//   Route   the links between two hosts, crossed in order by every transfer between them.
//   Cpu     c cores shared by runnable tasks: n tasks each progress at min(1, c / n) of a core.
//
// A transfer through several resources (a remote read: server disk then link) is one flow
// whose FlowSpec lists each resource's usage; see Disk::read_usage() and friends.

#include <pagecache/fair_share.hpp>
#include <pagecache/task.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace pagecache {

/// Disk bandwidths: what one stream gets alone, and what all streams together get.
struct DiskBandwidth {
  double read = 0.0;             ///< one stream, reading
  double write = 0.0;            ///< one stream, writing
  double aggregate_read = 0.0;   ///< all streams together, reading; 0: as one stream
  double aggregate_write = 0.0;  ///< all streams together, writing; 0: as one stream
  /// What shapes a stream besides its rate (each 0: not modelled, the disk as without it).
  /// Seconds before a request's data flow: a request of s bytes takes request_latency +
  /// s / bandwidth. The disk serves other requests meanwhile: only the stream waits.
  double request_latency = 0.0;
  std::int64_t read_ahead = 0;   ///< the largest readahead window (read_ahead_kb), bytes; 0 or >= 4 KiB
  std::int64_t max_request = 0;  ///< the largest request (max_sectors_kb), bytes; 0 (unlimited) or >= 4 KiB
  /// Bytes of a write cache in front of the medium (an SSD's SLC cache): a write fills it at
  /// `write` (all together up to `aggregate_write`), the medium drains it at `sustained_write`.
  std::int64_t write_cache = 0;
  /// The medium's write rate behind the write cache, for one stream and for all together:
  /// given with write_cache and only then; at most `write`.
  double sustained_write = 0.0;
};

class Disk {
 public:
  /// `capacity` is the storage size in bytes (0: unlimited). One stream may take the whole disk.
  Disk(FairShare& share, std::string name, double read_bw, double write_bw, std::int64_t capacity = 0);
  /// A disk whose streams together may go faster than one (aggregates >= the stream rates).
  Disk(FairShare& share, std::string name, DiskBandwidth bandwidth, std::int64_t capacity = 0);

  /// `bound`: the most the reader can take (e.g. Memory::fresh_copy_rate()). `request`: the
  /// reader issues requests of that many bytes one at a time (O_DIRECT at I/O depth 1), which
  /// bounds it at read_request_rate(request); 0: it keeps the disk's queue full.
  FlowAwaiter read(std::int64_t bytes, double bound = kUnbounded, std::int64_t request = 0) const;
  /// `request` as read()'s (writeback keeps the queue full: 0). The write takes its room in
  /// the write cache as it starts (see writing()).
  FlowAwaiter write(std::int64_t bytes, std::int64_t request = 0) const;
  /// Adds a read (a write) of the disk to a flow through other resources too: its share of
  /// the disk and, if a stream is slower than the disk, the stream's bound; `request` as
  /// read()'s.
  FlowSpec& reading(FlowSpec& spec, std::int64_t request = 0) const;
  /// With a write cache, call it once per write, as it starts: the write's `spec.work` bytes
  /// take the room the cache has then (a write under way holds all of its bytes in it, so
  /// that writes at once share the room first come, first served). The part that fits, with
  /// the medium draining the cache meanwhile, goes at `write`, the rest after it at
  /// `sustained_write`: the bound is the write's bytes over the time of both, and its share
  /// of the disk is theirs (the sustained part takes the medium alone). The plan is made as
  /// if the write went at its bound. Reads do not go through the cache (data still in it is
  /// read from the medium: not measured).
  FlowSpec& writing(FlowSpec& spec, std::int64_t request = 0) const;
  /// One stream issuing requests of `request` bytes one at a time:
  /// request / (request_latency + request / read (write)); the stream's rate for request 0
  /// (unbounded) or a disk without latency.
  double read_request_rate(std::int64_t request) const noexcept;
  double write_request_rate(std::int64_t request) const noexcept;
  Usage read_usage() const noexcept { return {resource_, 1.0 / aggregate_read_bw_}; }
  Usage write_usage() const noexcept { return {resource_, 1.0 / aggregate_write_bw_}; }

  const std::string& name() const { return share_->name(resource_); }
  ResourceId resource() const noexcept { return resource_; }
  /// One stream's rates.
  double read_bandwidth() const noexcept { return read_bw_; }
  double write_bandwidth() const noexcept { return write_bw_; }
  std::int64_t capacity() const noexcept { return capacity_; }
  double request_latency() const noexcept { return request_latency_; }
  std::int64_t read_ahead() const noexcept { return read_ahead_; }
  std::int64_t max_request() const noexcept { return max_request_; }
  std::int64_t write_cache() const noexcept { return write_cache_; }
  double sustained_write_bandwidth() const noexcept { return sustained_write_bw_; }
  /// Bytes in the write cache now: those of the writes started, less what the medium drained
  /// since (those of a write under way included). May exceed write_cache() while writes run.
  double write_cache_fill() const;

 private:
  /// Takes `bytes` of a write starting now into the write cache; returns how many go at the
  /// burst rate.
  double fill_write_cache(double bytes) const;

  FairShare* share_;
  ResourceId resource_;
  double read_bw_;
  double write_bw_;
  double aggregate_read_bw_;
  double aggregate_write_bw_;
  std::int64_t capacity_;
  double request_latency_;
  std::int64_t read_ahead_;
  std::int64_t max_request_;
  std::int64_t write_cache_;
  double sustained_write_bw_;
  // The write cache's level as of cache_time_: the device's state, which const users of the
  // disk (the files, the flusher) change by writing to it, as they load its FairShare.
  mutable double cache_fill_ = 0.0;
  mutable double cache_time_ = 0.0;
};

/// Memory bandwidths: per flow (one thread's copy) and aggregate (the whole memory system).
struct MemoryBandwidth {
  double read = 0.0;             ///< per-flow read (cache -> application buffer)
  double write = 0.0;            ///< per-flow write (application buffer -> cache)
  double aggregate_read = 0.0;   ///< all flows together, reading
  double aggregate_write = 0.0;  ///< all flows together, writing
  /// First touch of fresh application memory (docs/model.md §6.10): the page fault and the zeroing
  /// of each page a thread writes for the first time, in bytes per second of one thread;
  /// 0: free. A read into a newly allocated buffer pays it on top of the copy.
  double first_touch = 0.0;
  /// Writing into the page cache pages that the writer first reclaimed from clean cache (the
  /// kernel's direct reclaim: scanning, unmapping and freeing them, then the copy), in bytes
  /// per second of one thread; 0: as fast as into free pages (`write`, which is what a
  /// write into a cache with free memory measures).
  double reclaimed_write = 0.0;
  /// Memory a virtual machine's host took back (free page reporting, docs/model.md §6.16):
  /// the first write into such a page waits for the host to give it again, this many bytes
  /// per second of one thread on top of the write itself; 0: no memory is taken back.
  double cold_fault = 0.0;
  /// The host's faults of all threads together (its vCPUs fault in parallel); 0: cold_fault
  /// times the host's cores.
  double aggregate_cold_fault = 0.0;

  /// One channel shared by everything, as in the paper: the per-flow bounds equal the aggregate.
  static MemoryBandwidth shared_channel(double bandwidth) { return {bandwidth, bandwidth, bandwidth, bandwidth, 0.0, 0.0}; }
};

/// NUMA (docs/model.md §6.20): the rates of one thread, and of one node's threads together,
/// with the other node's memory, as fractions of the same with their own node's.
struct NumaRatios {
  double copy = 1.0;         ///< one thread's copy with either side on the other node
  double first_touch = 1.0;  ///< one thread's first touch (fault and zeroing) of the other node's pages
  double aggregate = 1.0;    ///< a node's threads together on the other node's memory (the interconnect)
};

/// NUMA nodes (docs/model.md §6.20): the host's memory, its aggregate memory bandwidth and
/// its cores split evenly among `nodes` nodes. Each thread runs on one node (Host::start_thread)
/// and takes new memory there first, then on the other node (no reclaim before that, as with
/// zone_reclaim_mode 0); each node reclaims its own data. One node: the host as without.
struct NumaSpec {
  int nodes = 1;      ///< 1 or 2
  NumaRatios remote;  ///< rates with the other node's memory, over the same with one's own
};

/// The shares of a copy's bytes whose source (cache pages read) and destination (pages
/// written: cache or application memory) are on another NUMA node than the copying thread's.
struct RemoteShare {
  double source = 0.0;
  double destination = 0.0;
};

class Cpu;

class Memory {
 public:
  Memory(FairShare& share, std::string name, MemoryBandwidth bandwidth);

  /// Copies (read, write, read_into_fresh) are done by a thread of `cpu` and hold one of its
  /// cores while they run, sharing the cores with computations as the kernel's scheduler
  /// shares them among runnable threads: a copy also crosses the CPU, a core's worth at its
  /// bound, and weighs its bound so that a copy and a computation each get an equal share of
  /// a core. nullptr (the default): copies take no CPU. The specs (read_spec ...) are not
  /// charged: they are parts of transfers through other devices.
  void copy_on(const Cpu* cpu) noexcept { cpu_ = cpu; }

  /// Makes this memory one NUMA node's of a host with another: copies by its threads with a
  /// remote share (the `remote` arguments below) go at `ratios` of its rates for that share,
  /// and a remote byte costs this node's aggregate 1 / ratios.aggregate of a local one (the
  /// interconnect, folded into the node: each copy stays one flow on one resource). Throws
  /// ConfigError, naming `name`, for a ratio not > 0.
  void set_numa(NumaRatios ratios, const std::string& name);

  FlowAwaiter read(std::int64_t bytes, RemoteShare remote = {}) const;
  /// A write of `bytes` into the page cache, `reclaimed` of them into pages the writer
  /// reclaimed for it and `cold` into pages the host took back: one after the other, at
  /// `write` and `reclaimed_write`, plus `cold` bytes at `cold_fault`.
  FlowAwaiter write(std::int64_t bytes, std::int64_t reclaimed = 0, std::int64_t cold = 0, RemoteShare remote = {}) const;
  /// Flow specs for use in a multi-resource flow (bound included).
  FlowSpec read_spec(std::int64_t bytes, RemoteShare remote = {}) const;
  FlowSpec write_spec(std::int64_t bytes, std::int64_t reclaimed = 0, std::int64_t cold = 0, RemoteShare remote = {}) const;
  /// A cached read into fresh application memory: the copy and the first touch of every
  /// destination page, done one after the other by the reading thread (its rate is
  /// 1 / (1 / read + 1 / first_touch)); the zeroing also loads the aggregate as a write.
  /// `cold_share`: the fraction of the destination pages the host took back.
  FlowSpec read_into_fresh_spec(std::int64_t bytes, double cold_share = 0.0, RemoteShare remote = {}) const;
  FlowAwaiter read_into_fresh(std::int64_t bytes, double cold_share = 0.0, RemoteShare remote = {}) const;
  /// The fastest a thread can take data into fresh application memory (copy and first
  /// touch): the bound of a device read into a new buffer. Unbounded if first touch is free
  /// and no page is cold.
  double fresh_copy_rate(double cold_share = 0.0, RemoteShare remote = {}) const noexcept;
  /// `rate` slowed by the host's faults on `cold_share` of the bytes (rate itself if none).
  double with_cold(double rate, double cold_share) const noexcept;
  /// A device read of `bytes` into new cache pages and a new buffer, `cold_share` bytes of
  /// them per byte read cold: bounded by `bound`, and its faults share the host's.
  FlowAwaiter device_read(const Disk& disk, std::int64_t bytes, double bound, double cold_share) const;

  ResourceId resource() const noexcept { return resource_; }
  const MemoryBandwidth& bandwidth() const noexcept { return bandwidth_; }

 private:
  /// `spec` as a copy by a thread on cpu_ (copy_on), if any.
  FlowSpec on_core(FlowSpec spec) const;

  /// `spec` also through the host's faults for `cold_share` of its bytes.
  FlowSpec& faulting(FlowSpec& spec, double cold_share) const;
  /// `spec` loading the memory `cost` per byte, `share` of it remote (at 1 / ratios_.aggregate).
  FlowSpec& load(FlowSpec& spec, double cost, double share) const;
  /// One thread's `rate` with `share` of its bytes on the other node, at `ratio` of it there.
  static double remote_rate(double rate, double share, double ratio) noexcept {
    return share > 0.0 && ratio != 1.0 ? rate / (1.0 + share * (1.0 / ratio - 1.0)) : rate;  // remote bytes at `ratio` of it
  }

  FairShare* share_;
  ResourceId resource_;
  ResourceId faults_{};  // the host's faults into cold memory, with cold_fault only
  MemoryBandwidth bandwidth_;
  const Cpu* cpu_ = nullptr;
  bool numa_ = false;  // one node of several (set_numa)
  NumaRatios ratios_;
};

enum class LinkSharing {
  Shared,   ///< the flows crossing it share its bandwidth
  Fatpipe,  ///< every flow may take its whole bandwidth (a backbone no flow can saturate)
};

class Link {
 public:
  Link(FairShare& share, std::string name, double bandwidth, double latency, LinkSharing sharing = LinkSharing::Shared);

  /// Sends `bytes` over the link alone: latency, then the transfer.
  Task<void> send(std::int64_t bytes) const;
  /// Sends `spec` (whose other resources are already listed) across the link too: latency,
  /// then one flow through all of them.
  Task<void> send_through(FlowSpec spec) const;
  /// Adds the link to a flow: a shared link as a resource it crosses, a fatpipe as a bound.
  FlowSpec& carry(FlowSpec& spec) const;
  Usage usage() const noexcept { return {resource_, 1.0 / bandwidth_}; }

  ResourceId resource() const noexcept { return resource_; }
  double bandwidth() const noexcept { return bandwidth_; }
  double latency() const noexcept { return latency_; }
  LinkSharing sharing() const noexcept { return sharing_; }
  FairShare& share() const noexcept { return *share_; }

 private:
  FairShare* share_;
  ResourceId resource_;
  double bandwidth_;
  double latency_;
  LinkSharing sharing_;
};

/// The links between two hosts, in the order a transfer crosses them (SimGrid's route). A
/// transfer pays the sum of their latencies once, then is one flow through all of them, so the
/// most loaded sets its pace. The links must outlive the route.
class Route {
 public:
  /// At least one link. A flow crosses at most kMaxResourcesPerFlow resources, its ends (a
  /// disk, the memories) included: a route of more shared links fails when it is used.
  explicit Route(std::vector<const Link*> links);

  /// Sends `bytes` over the route alone.
  Task<void> send(std::int64_t bytes) const;
  /// Sends `spec` (whose other resources are already listed) along the route too.
  Task<void> send_through(FlowSpec spec) const;

  double latency() const noexcept { return latency_; }
  const std::vector<const Link*>& links() const noexcept { return links_; }

 private:
  std::vector<const Link*> links_;
  double latency_ = 0.0;
};

class Cpu {
 public:
  Cpu(FairShare& share, std::string name, int cores);

  /// Runs `core_seconds` of computation on one core's worth of the CPU at most.
  FlowAwaiter compute(double core_seconds) const;

  ResourceId resource() const noexcept { return resource_; }
  int cores() const noexcept { return cores_; }

 private:
  FairShare* share_;
  ResourceId resource_;
  int cores_;
};

}  // namespace pagecache
