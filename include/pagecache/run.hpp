#pragma once
// Running a scenario and what a run produces: the phase timeline, the memory profile, the
// cache contents after every I/O phase, and a summary (docs/model.md §8). Their writers live
// outside the model, in the report layer: pagecache/outputs.hpp writes what `pcsim run` writes.

#include <pagecache/memory_state.hpp>
#include <pagecache/scenario.hpp>
#include <pagecache/trace.hpp>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace pagecache {

/// One phase (read, compute or write) of one task: 56 bytes, names interned (a run of 10^5
/// pipelines has 9 x 10^5 rows). The names are in RunResult::names: RunResult::app_name(row)
/// and task_name(row) give them; RunResult::host_name(row) where the task ran.
struct PhaseRow {
  std::uint32_t app = 0;   ///< the application's name: its index in RunResult::names
  std::uint32_t task = 0;  ///< the task's name: its index in RunResult::names
  PhaseKind phase = PhaseKind::Read;
  std::uint32_t host = 0;  ///< the host the task ran on: its index in RunResult::hosts
  double start = 0.0;
  double end = 0.0;
  std::int64_t bytes = 0;        ///< what the task asked for: bytes = cache_bytes + disk_bytes
  std::int64_t cache_bytes = 0;  ///< of those, found in the page cache from before (or written into it)
  /// Of those, read from (or written through to) the device during the phase, readahead the
  /// phase used included; what the device read beyond all it used is in neither.
  std::int64_t disk_bytes = 0;
};

/// A host's memory at one instant.
struct MemoryRow {
  double time = 0.0;
  std::uint32_t host = 0;  ///< its index in RunResult::hosts
  MemoryState state;
};

/// Bytes of one file in its host's page cache after an I/O phase of a task: 16 bytes, for there
/// is a row per file and I/O phase (1,000 pipelines of four files make 24 million).
struct CacheRow {
  std::uint32_t phase = 0;  ///< the I/O phase: its row in RunResult::timeline (app, task, read or write)
  std::uint32_t file = 0;   ///< the file: its name in RunResult::files
  std::int64_t cached = 0;
};

struct PhaseTotals {
  double seconds = 0.0;  ///< summed over tasks
  std::int64_t bytes = 0;
};

struct RunSummary {
  double makespan = 0.0;           ///< when the last task ended
  double end_time = 0.0;           ///< when the last event ran (dirty data written back)
  PhaseTotals read, compute, write;
  std::int64_t disk_read_bytes = 0;
  std::int64_t cache_read_bytes = 0;
  std::int64_t forced_flush_bytes = 0;    ///< written back by writers (dirty limit, room)
  std::int64_t periodic_flush_bytes = 0;  ///< written back by the flusher
  std::int64_t evicted_bytes = 0;
  std::int64_t peak_dirty_bytes = 0;
  std::uint64_t events = 0;
  std::uint64_t chunk_operations = 0;  ///< chunks read and written by the applications
  double wall_seconds = 0.0;  ///< the simulator's own run time
  double events_per_second = 0.0;
};

struct RunResult {
  std::vector<PhaseRow> timeline;
  std::vector<MemoryRow> memory;
  /// The applications' and tasks' names, each once, what PhaseRow::app and ::task name.
  std::vector<std::string> names;
  /// The scenario's hosts, in its order, what MemoryRow::host and PhaseRow::host name.
  std::vector<std::string> hosts;
  /// The scenario's files, in its order, what CacheRow::file names (empty if the cache contents
  /// are not recorded).
  std::vector<std::string> files;
  /// The cache contents: after each I/O phase, every file, in `files` order.
  std::vector<CacheRow> cache;
  /// Empty if `cache` holds the cache contents; otherwise why they were not recorded.
  std::string cache_not_recorded;
  RunSummary summary;

  const std::string& app_name(const PhaseRow& row) const { return names[row.app]; }
  const std::string& task_name(const PhaseRow& row) const { return names[row.task]; }
  const std::string& host_name(const MemoryRow& row) const { return hosts[row.host]; }
  const std::string& host_name(const PhaseRow& row) const { return hosts[row.host]; }
};

struct RunOptions {
  /// Record cache contents (every file, after every I/O phase).
  bool cache_contents = true;
  /// The cache contents are not recorded (see RunResult::cache_not_recorded) if they would
  /// take more rows than this. Their rows are files x I/O phases, which grows with the square
  /// of the number of applications: 1,000 pipelines of four files make 24 million.
  std::size_t max_cache_rows = 1'000'000;
  /// Called now and then during the run with the simulated time and the events so far.
  std::function<void(double, std::uint64_t)> progress;
  /// The run stops with a SimulationError once its clock passes this many seconds (checked
  /// every few thousand events): beyond, double-precision time loses the microsecond.
  double max_simulated_time = 1e10;
  /// Consumers of the run's events (trace.hpp), beside the recorder of the RunResult: each
  /// must outlive the run. With none, the devices and page caches report nothing.
  std::vector<TraceSink*> consumers;
};

/// Runs the scenario to the end. Throws SimulationError (with the simulated time) if the
/// simulation cannot proceed, e.g. a task needs more memory than its host has.
RunResult run_scenario(const Scenario& scenario, const RunOptions& options = {});

/// As above, for a caller done with the scenario: its applications and files are freed once
/// the run is planned, before it starts (at 10^5 pipelines they are a large share of a run's
/// memory). The results are the same.
RunResult run_scenario(Scenario&& scenario, const RunOptions& options = {});

}  // namespace pagecache
