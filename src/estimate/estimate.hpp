#pragma once
// What a run of a resolved scenario will cost, estimated from the scenario alone before it runs,
// in time linear in its tasks, files and hosts (no simulation): how long it simulates, and how
// many events it takes, source by source (docs/model.md §3-§7). check_limits (limits.hpp) holds
// the estimate against ScenarioLimits; the estimate names, for each figure, the element of the
// scenario that drives it, so that a refusal can name its key.

#include <pagecache/scenario.hpp>

#include <cstddef>
#include <optional>
#include <string>

namespace pagecache::estimate {

/// The longest stretch of simulated time the run must cover, and what takes it.
struct Stretch {
  enum class Kind : unsigned char {
    None,
    Disk,         ///< a disk moving its bytes: host, disk
    Memory,       ///< a host's memory copying its bytes: host
    Cores,        ///< a host's cores computing its tasks' CPU seconds: host
    Link,         ///< a link carrying its bytes: link
    Application,  ///< an application's tasks one after the other: app (task, link)
    Workflow,     ///< a workflow's tasks over its hosts' cores: workflow (task, link)
  };
  Kind kind = Kind::None;
  double seconds = 0.0;
  std::size_t index = 0;  ///< the host, link, application or workflow
  std::size_t disk = 0;   ///< Disk: the host's disk
  bool reading = false;   ///< Disk, Memory: reads take longer than writes
  /// Application, Workflow: waiting for the latency of its routes takes longer than
  /// computing; `link` is then the link of highest latency it crosses.
  bool latency = false;
  std::size_t link = 0;
  std::size_t task = 0;  ///< Application, Workflow: its longest computing task
  std::string what;      ///< what takes that long, for a message
};

/// A task of the scenario: of an application, or of a workflow.
struct TaskAt {
  bool workflow = false;
  std::size_t owner = 0;  ///< the application's or the workflow's index
  std::size_t task = 0;
};

struct RunEstimate {
  Stretch longest;
  /// Each file's bytes over its task's chunk size, for every read and write.
  double chunk_operations = 0.0;
  TaskAt most_operations;  ///< the task with the most
  /// Its access (AccessSpec, by index) with the most, if its accesses make most of them.
  std::optional<std::size_t> most_operations_access;

  /// Events, by source:
  /// - each chunk's transfers (device, memory, route and its latency) and the writeback of the
  ///   data written (by writers, reclaim, background writeback or expiry: once either way),
  ///   each task's start, computation, fsync and deletions;
  double transfer_events = 0.0;
  /// - throttled writers' pauses (the kernel's dirty throttling: at most 1 s each, and at least
  ///   one per chunk written while throttled);
  double throttle_events = 0.0;
  /// - the flushers' wake-ups, every writeback_interval while their host has dirty data;
  double flusher_events = 0.0;
  /// - the memory sampler's ticks, every memory_sample_interval while memory changes.
  double sampler_events = 0.0;
  std::size_t most_throttled_host = 0;  ///< the host whose writers pause most
  double most_throttled_pauses = 0.0;
  std::size_t busiest_flusher = 0;  ///< the host whose flusher wakes most
  double busiest_flusher_wakeups = 0.0;

  /// memory.csv rows (held in memory until written).
  double memory_rows = 0.0;

  double events() const noexcept { return transfer_events + throttle_events + flusher_events + sampler_events; }
};

/// The estimate for `s`, whose references are resolved (every file, host and route named exists).
RunEstimate estimate_run(const Scenario& s);

}  // namespace pagecache::estimate
