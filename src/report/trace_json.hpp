#pragma once
// trace.json: a run in the Chrome Trace Event format, which Perfetto UI (ui.perfetto.dev) and
// chrome://tracing open. Timestamps are microseconds of simulated time.
//   pid 1, "applications": a track (tid) per application, its phases as complete slices
//          ("X" named "TASK read", "TASK compute" or "TASK write"; args task, host, bytes, cache
//          and disk bytes). Tasks of one workflow that overlap take further lanes of its
//          track ("app #2", ...).
//   pid 2 + h, "host NAME": counters of its memory (free, anonymous, cached clean, dirty,
//          writeback, bytes), instants for flushes (by cause) and evictions, and the writers'
//          throttling pauses as async slices.
//   pid 2 + hosts, "devices": every transfer through the fair-share model as an async slice
//          named after the first resource it crossed (args: bytes or core-seconds, the route).

#include <pagecache/trace.hpp>

#include <fmt/format.h>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace pagecache::report {

class TraceJson final : public TraceSink {
 public:
  /// Past `max_bytes` of events the flows, flushes, evictions and pauses are dropped (phases
  /// and memory counters are kept) and truncated() says so: a trace of a huge run stays usable.
  explicit TraceJson(std::size_t max_bytes = std::size_t{1} << 30) : max_bytes_(max_bytes) {}

  void on_start(const TraceStart& start) override;
  void on_phase(const PhaseEvent& e) override;
  void on_flow(const FlowEvent& e) override;
  void on_flush(const FlushEvent& e) override;
  void on_eviction(const EvictionEvent& e) override;
  void on_throttle(const ThrottleEvent& e) override;
  void on_memory(const MemoryEvent& e) override;

  /// The whole document; `scenario` names the run in its metadata.
  std::string text(const std::string& scenario) const;
  bool truncated() const noexcept { return truncated_; }

 private:
  // An application's lanes: each the tid and the end of its last phase; a task keeps its lane.
  struct Lane {
    std::uint32_t tid;
    double last_end;
  };
  struct AppTrack {
    std::vector<Lane> lanes;
    std::map<std::string, std::size_t, std::less<>> task_lane;
  };
  Lane& lane_for(std::string_view app, std::string_view task, double start);
  bool room_for_detail();
  std::uint32_t host_pid(std::uint32_t host) const { return 2 + host; }

  std::size_t max_bytes_;
  bool truncated_ = false;
  std::vector<std::string> hosts_;
  std::map<std::string, AppTrack, std::less<>> apps_;
  std::uint32_t next_tid_ = 1;
  std::uint64_t next_id_ = 1;  // of async slices
  fmt::memory_buffer metadata_;
  fmt::memory_buffer events_;
};

}  // namespace pagecache::report
