#pragma once
// TraceSink: what happens in a run, reported as it happens. The runner reports phases, memory
// rows and cache contents; the fair-share model reports flows on the devices; the page cache
// reports flushes (with their cause), evictions and throttling pauses. Every output of a run is
// a consumer: RunResult's rows are recorded by one, report.html and trace.json are others, and
// a new output needs no new hooks. With no consumer attached, each hook costs one test of a
// null pointer.
//
// Events come in simulated-time order of their report, which for an event with a span (a
// phase, a flow, a pause) is its end. Names passed as string_view live as long as the run.

#include <pagecache/memory_state.hpp>

#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace pagecache {

enum class PhaseKind : std::uint8_t { Read, Compute, Write };

/// "read", "compute", "write".
std::string_view to_string(PhaseKind kind) noexcept;

/// Why dirty data was written back.
enum class FlushCause : std::uint8_t {
  DirtyLimit,  ///< a writer over the dirty threshold wrote back (paper's Algorithm 3)
  Reclaim,     ///< dirty data written back to free memory for a read or a write
  Background,  ///< the flusher, dirty data over the background threshold
  Expiry,      ///< the flusher's periodic writeback of data dirty for longer than dirty_expire
  Fsync,       ///< a task's fsync
};

/// "dirty_limit", "reclaim", "background", "expiry", "fsync".
std::string_view to_string(FlushCause cause) noexcept;

/// What the run is made of, reported once before anything else.
struct TraceStart {
  std::span<const std::string> hosts;  ///< in the scenario's order; the host indices below
  std::span<const std::string> files;  ///< in the scenario's order; CacheContents' order
};

/// One phase of one task, at its end. `row` numbers the phases in the order they end (the row
/// of RunResult::timeline).
struct PhaseEvent {
  std::uint32_t row = 0;
  std::uint32_t host = 0;
  std::string_view app;
  std::string_view task;
  PhaseKind kind = PhaseKind::Read;
  double start = 0.0;
  double end = 0.0;
  std::int64_t bytes = 0;
  std::int64_t cache_bytes = 0;  ///< read from (or written into) the page cache
  std::int64_t disk_bytes = 0;   ///< read from (or written to) the device
};

/// A transfer through the fair-share model, at its end: bytes (or core-seconds for a CPU)
/// through the resources it crossed, in order (a remote read: the server's disk, the links).
struct FlowEvent {
  double start = 0.0;
  double end = 0.0;
  double work = 0.0;
  std::span<const std::string_view> resources;
};

/// Dirty data taken for writing back on a host, at the moment it is taken.
struct FlushEvent {
  std::uint32_t host = 0;
  double time = 0.0;
  FlushCause cause = FlushCause::Background;
  std::int64_t bytes = 0;
};

/// Clean cached data dropped on a host to make room.
struct EvictionEvent {
  std::uint32_t host = 0;
  double time = 0.0;
  std::int64_t bytes = 0;
};

/// A writer held by dirty throttling (balance_dirty_pages), at the end of the pause.
struct ThrottleEvent {
  std::uint32_t host = 0;
  double start = 0.0;
  double end = 0.0;
};

/// A row of the memory profile: a host's memory when it changed (or at a sampling tick).
struct MemoryEvent {
  std::uint32_t host = 0;
  double time = 0.0;
  MemoryState state;
};

/// The page cache contents after an I/O phase: bytes cached of every file, in TraceStart's order.
struct CacheContentsEvent {
  std::uint32_t phase_row = 0;  ///< the PhaseEvent::row of the phase just ended
  std::span<const std::int64_t> cached;
};

/// The observer of a run. Every method has an empty default: a consumer overrides what it uses.
class TraceSink {
 public:
  virtual ~TraceSink() = default;
  /// Whether it wants on_flow: following every transfer costs a lookup per flow, which a run
  /// spares when no consumer asks for them.
  virtual bool wants_flows() const { return true; }
  virtual void on_start(const TraceStart&) {}
  virtual void on_phase(const PhaseEvent&) {}
  virtual void on_flow(const FlowEvent&) {}
  virtual void on_flush(const FlushEvent&) {}
  virtual void on_eviction(const EvictionEvent&) {}
  virtual void on_throttle(const ThrottleEvent&) {}
  virtual void on_memory(const MemoryEvent&) {}
  virtual void on_cache_contents(const CacheContentsEvent&) {}
  /// The run is over: the last event ran at `time`.
  virtual void on_end(double /*time*/) {}
};

}  // namespace pagecache
