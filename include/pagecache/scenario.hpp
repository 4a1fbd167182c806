#pragma once
// Scenario: everything one simulation run needs — the platform (hosts, their memory, disks
// and page-cache settings), the files, and the workload — fully resolved (units converted,
// defaults filled, shorthands expanded). Loaded from a TOML file by load_scenario()
// (scenario_file.hpp, the scenario layer); see the
// README for the format. Run by run_scenario() (pagecache/run.hpp).

#include <pagecache/cache_settings.hpp>
#include <pagecache/devices.hpp>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace pagecache {

/// A model profile: `paper` reproduces WRENCH-cache (the paper's simulator); `linux`
/// follows the kernel.
enum class Profile { Paper, Linux };

const char* to_string(Profile profile);
CacheSettings settings_for(Profile profile);

struct DiskSpec {
  std::string name;
  double read_bw = 0.0;   ///< one stream
  double write_bw = 0.0;  ///< one stream
  double aggregate_read_bw = 0.0;   ///< all streams together; 0: as one stream
  double aggregate_write_bw = 0.0;  ///< all streams together; 0: as one stream
  std::int64_t capacity = 0;  ///< bytes; 0: unlimited
  /// DiskBandwidth's fields of these names (0: not modelled): seconds per request, the largest
  /// readahead window and request in bytes, the write cache in bytes and the medium's rate
  /// behind it (given together).
  double request_latency = 0.0;
  std::int64_t read_ahead = 0;
  std::int64_t max_request = 0;
  std::int64_t write_cache = 0;
  double sustained_write_bw = 0.0;
};

struct HostConfig {
  std::string name;
  int cores = 1;
  /// Speed of one core in flop/s (a SimGrid host's speed; a TOML host's `speed`); 0: not
  /// given. Only a workflow file's compute = "speed" reads it (WorkflowImport).
  double speed = 0.0;
  std::int64_t memory = 0;
  /// Memory neither free nor reclaimable at the start (e.g. tmpfs contents): counted as
  /// application memory for the whole run.
  std::int64_t memory_in_use = 0;
  MemoryBandwidth memory_bandwidth;
  /// Free page reporting (with memory_bandwidth.cold_fault): HostSpec's fields of these names.
  double page_reporting_delay = 2.0;
  std::int64_t memory_freed_at_start = 0;
  /// HostSpec's field of this name: seconds per request of a read or write by parts.
  double request_time = 0.0;
  CacheSettings cache;
  std::vector<DiskSpec> disks;
  /// [hosts.numa]: HostSpec's field of this name (one node unless given).
  NumaSpec numa;
};

/// A network link. Given its two hosts, it is also the route between them: a task on one may
/// use the other's files through it (as over an NFS mount). Without, it is crossed only by the
/// routes that name it (a platform file's links).
struct LinkSpec {
  std::string name;
  double bandwidth = 0.0;
  double latency = 0.0;
  std::string host_a;
  std::string host_b;
  LinkSharing sharing = LinkSharing::Shared;
};

/// The links between two hosts, in the order a transfer from host_a to host_b crosses them
/// (SimGrid's route; the same links serve the other direction).
struct RouteSpec {
  std::string host_a;
  std::string host_b;
  std::vector<std::string> links;
};

struct FileSpec {
  std::string name;
  std::int64_t size = 0;
  std::string host;  ///< where it is stored
  std::string disk;
  bool cached = false;  ///< in its host's page cache (clean) at time 0
};

/// Many files of one size stored together, e.g. a training data set: `count` files named
/// `name/0` ... `name/{count-1}`, made when the run starts (never a FileSpec each: a set of 10^6
/// is one entry). Tasks read its files through AccessSpec only.
struct FileSetSpec {
  std::string name;
  std::int64_t count = 0;  ///< files, >= 1
  std::int64_t size = 0;   ///< bytes of each
  std::string host;        ///< where they are stored
  std::string disk;
  bool cached = false;  ///< all in their host's page cache (clean) at time 0
};

/// The order in which an access visits its files (a file set's), or a file's parts (one file's).
enum class AccessPattern {
  Sequential,  ///< files 0, 1, ... (parts from the region's start) in order, the same every epoch
  Random,      ///< a seeded draw, new each epoch (AccessSpec::replacement)
  Strided,     ///< one file: requests `stride` bytes apart from the region's start
  Ranges,      ///< one file: the listed ranges, in order
};

/// What an access of one file does with its requests.
enum class AccessMode {
  Read,
  Write,   ///< in place where cached, new dirty data elsewhere (Host::write_ranges)
  Append,  ///< a sequential write from the region's start to the file's end
};

/// posix_fadvise advice an access of one file gives before it reads (Host's ReadAdvice).
enum class AccessAdvice { Normal, Sequential, Random };

const char* to_string(AccessPattern pattern);
const char* to_string(AccessMode mode);
const char* to_string(AccessAdvice advice);

/// A task's reads over a file set, in epochs (a training job's passes over its data set): each
/// epoch reads `count` files of the set, each whole in the task's chunks (as a `read` of that
/// file), and frees each file's buffer once it is read (a data loader keeps no sample).
/// Or, with `file` instead of `file_set`, its reads or writes of parts of one file (a
/// hyperslab, a key-value store's pages, a log's appends), in requests of `request` bytes that
/// the page cache serves by byte range (Host::read_ranges, write_ranges), epoch after epoch.
struct AccessSpec {
  std::string file_set;  ///< FileSetSpec::name; empty for an access of one file
  std::string file;      ///< FileSpec::name of the file accessed by parts; empty for a file set's
  AccessPattern pattern = AccessPattern::Sequential;
  /// Random: the generator's seed; the same seed gives the same orders.
  std::uint64_t seed = 0;
  /// Random: false, each file (part) at most once per epoch (a new shuffle each epoch); true,
  /// `count` independent draws.
  bool replacement = false;
  /// Files per epoch, 0: the set's count (without replacement, at most it); of one file, requests
  /// per epoch, 0: each part of the region once (strided: as many as fit; ranges: unused).
  std::int64_t count = 0;
  std::int64_t repeat = 1;  ///< epochs, >= 1
  // Of one file only:
  std::int64_t request = 0;  ///< bytes per request, > 0 (ranges: each range cut into such requests)
  /// The region the requests fall in, [offset, offset + length), within the file (ranges: unused).
  std::int64_t offset = 0;
  std::int64_t length = 0;
  std::int64_t stride = 0;  ///< strided: bytes from one request's start to the next's, >= request
  std::vector<std::pair<std::int64_t, std::int64_t>> ranges;  ///< ranges: (offset, length) each
  AccessMode mode = AccessMode::Read;
  AccessAdvice advice = AccessAdvice::Normal;  ///< reads only
  /// One file, random: each epoch a draw of its own (true), or every epoch epoch 1's requests
  /// again (false: fio's randrepeat, which reseeds at each loop).
  bool reshuffle = true;
  /// One file: before each epoch the region's clean cached data is dropped (POSIX_FADV_DONTNEED
  /// over it, or over each range), as fio's invalidate=1 does each time a job opens its file.
  bool invalidate = false;
  /// One file: after each epoch (after the task's fsync of it) the region's clean cached data
  /// is dropped, as fio does with a file it lays out (writes, fsyncs, POSIX_FADV_DONTNEED).
  bool drop_after = false;
  /// One file: no request starts this many seconds after the access began, whatever epoch it
  /// is in (fio's runtime); 0: no limit.
  double runtime = 0.0;
};

/// One task: read files, compute, write files, then release its buffers.
/// A memory group's limits (a cgroup's memory.max and memory.high; 0: none).
struct MemoryLimits {
  std::int64_t max = 0;
  std::int64_t high = 0;  ///< needs max
};

struct TaskSpec {
  std::string name;
  /// Where a workflow task runs; empty: on a host of its workflow's (WorkflowSpec::hosts).
  std::string host;
  /// Cores it holds while it runs (workflow tasks: it waits until its host has them free).
  int cores = 1;
  /// Application memory it holds from its start to its end, the buffers of what it reads
  /// included: a task reading more holds what it reads (bytes; 0: only its buffers).
  std::int64_t memory = 0;
  std::vector<std::string> reads;
  /// After `reads` and before computing, in order; a timeline row per access and epoch.
  std::vector<AccessSpec> accesses;
  double compute = 0.0;  ///< CPU seconds (on one core)
  std::vector<std::string> writes;
  std::int64_t chunk_size = 0;
  std::vector<std::string> after;  ///< workflow tasks that must end first (besides file producers)
  bool fsync = false;      ///< fsync each written file before the task ends
  bool direct_io = false;  ///< reads and writes bypass the page cache (O_DIRECT)
  std::vector<std::string> deletes;  ///< files deleted when the task ends
  /// Workflow tasks: each task with a memory_max runs in a memory group of its own, made on
  /// the host it runs on when it starts (as a workflow system on Kubernetes or Slurm runs
  /// each task as a pod or job with a memory limit). The group outlives the task: its page
  /// cache stays charged to it (the kernel's offline cgroup keeps its charges).
  MemoryLimits memory_limits;
};

/// An application: tasks run one after the other on one host.
struct AppSpec {
  std::string name;
  std::string host;
  std::vector<TaskSpec> tasks;
  /// Its memory group's limit (a cgroup's memory.max, as a batch system gives each job): its
  /// tasks' memory and the page cache of the files it touches first may not exceed it
  /// (Host::add_memory_group). 0: no group.
  std::int64_t memory_max = 0;
  /// memory.high (0: none; needs memory_max): above it the group reclaims its own data.
  std::int64_t memory_high = 0;
  /// Applications listed before it that must have ended before it starts (as fio's stonewall
  /// and wait_for order jobs); by name, each naming one of them. Empty: it starts at 0.
  std::vector<std::string> after;
};

/// A fio job that an application of the scenario runs ([fio]), as fio's JSON output names it
/// (pcsim run writes fio.json for them).
struct FioJobInfo {
  std::string app;      ///< the application that runs it
  std::string jobname;  ///< fio's "jobname" (a clone's is its job's)
  int groupid = 0;
  std::int64_t read_ios = 0;   ///< requests it reads, all loops and files together
  std::int64_t write_ios = 0;  ///< requests it writes
  /// fio's "job options": the options its own section sets, as written.
  std::vector<std::pair<std::string, std::string>> options;
};

/// The fio job file a scenario runs ([fio]); empty otherwise.
struct FioRun {
  std::string file;
  std::vector<std::pair<std::string, std::string>> global_options;  ///< fio's "global options"
  std::vector<FioJobInfo> jobs;  ///< in fio's order
};

/// A workflow: a DAG of tasks, each started when its inputs are ready (the tasks that write
/// them, and those named in `after`, have ended) and its host has the cores it needs free.
/// A task without a host of its own goes to the first of `hosts` with enough free cores the
/// moment it is ready; tasks waiting for cores are served in the order they became ready,
/// each as soon as some host has room for it.
struct WorkflowSpec {
  std::string name = "workflow";
  std::vector<std::string> hosts;  ///< at least one
  std::vector<TaskSpec> tasks;
  /// The workflow file it was read from (WfFormat JSON); empty if written in the scenario.
  std::string source;
};

struct Scenario {
  std::string source;  ///< the file it was read from ("<embedded>" for the default)
  std::string title;
  Profile profile = Profile::Linux;
  /// 0: one memory.csv row per change; else a host's row at each tick of this interval
  /// (seconds) at which its memory differs from its previous row.
  double memory_sample_interval = 1.0;
  /// `pcsim run` writes trace.json (Chrome Trace Event format) beside the other outputs.
  bool trace = false;
  std::vector<HostConfig> hosts;
  std::vector<LinkSpec> links;
  std::vector<RouteSpec> routes;
  std::vector<FileSpec> files;
  std::vector<FileSetSpec> file_sets;  ///< names distinct from the files'
  std::vector<AppSpec> apps;
  std::vector<WorkflowSpec> workflows;
  FioRun fio;
  /// What the inputs hold that pcsim read but does not model, and what it took in place of a
  /// value beyond its range: "file:line: what", for the user to see (pcsim prints them).
  std::vector<std::string> warnings;
};

/// The links a transfer between two different hosts crosses: their route's, or the link
/// joining them; empty if none.
std::vector<const LinkSpec*> route_between(const Scenario& scenario, const std::string& a, const std::string& b);

}  // namespace pagecache
