#pragma once
// ResultRecorder: the consumer that makes a run's RunResult (timeline, memory profile, cache
// contents) from what the runner reports. Always attached; other consumers come beside it.

#include <pagecache/run.hpp>
#include <pagecache/trace.hpp>

#include <cstdint>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace pagecache::workload {

class ResultRecorder final : public TraceSink {
 public:
  /// `phases`: the timeline's rows, reserved so that its peak is its size; `cache_rows`: the
  /// cache contents' rows if they are recorded, else 0 (RunResult::cache_not_recorded says why).
  ResultRecorder(std::size_t phases, std::size_t cache_rows, std::string cache_not_recorded) {
    result_.timeline.reserve(phases);
    result_.cache.reserve(cache_rows);  // growing by doubling touched up to twice its memory
    result_.cache_not_recorded = std::move(cache_not_recorded);
  }

  void on_start(const TraceStart& start) override {
    result_.hosts.assign(start.hosts.begin(), start.hosts.end());
    if (result_.cache_not_recorded.empty()) result_.files.assign(start.files.begin(), start.files.end());
  }
  void on_phase(const PhaseEvent& e) override {
    result_.timeline.push_back({.app = intern(e.app),
                                .task = intern(e.task),
                                .phase = e.kind,
                                .host = e.host,
                                .start = e.start,
                                .end = e.end,
                                .bytes = e.bytes,
                                .cache_bytes = e.cache_bytes,
                                .disk_bytes = e.disk_bytes});
  }
  void on_memory(const MemoryEvent& e) override { result_.memory.push_back({e.time, e.host, e.state}); }
  void on_cache_contents(const CacheContentsEvent& e) override {
    std::uint32_t file = 0;
    for (const std::int64_t cached : e.cached) result_.cache.push_back({e.phase_row, file++, cached});
  }

  RunResult& result() noexcept { return result_; }

 private:
  // A name's index in RunResult::names, added the first time it is met.
  std::uint32_t intern(std::string_view name) {
    const auto [it, added] = index_.try_emplace(std::string(name), static_cast<std::uint32_t>(result_.names.size()));
    if (added) result_.names.emplace_back(name);
    return it->second;
  }

  std::unordered_map<std::string, std::uint32_t> index_;
  RunResult result_;
};

/// Passes every event to each of its consumers, in order.
class TraceFanout final : public TraceSink {
 public:
  explicit TraceFanout(std::vector<TraceSink*> consumers) : consumers_(std::move(consumers)) {}
  void on_start(const TraceStart& e) override { for (TraceSink* c : consumers_) c->on_start(e); }
  void on_phase(const PhaseEvent& e) override { for (TraceSink* c : consumers_) c->on_phase(e); }
  void on_flow(const FlowEvent& e) override { for (TraceSink* c : consumers_) c->on_flow(e); }
  void on_flush(const FlushEvent& e) override { for (TraceSink* c : consumers_) c->on_flush(e); }
  void on_eviction(const EvictionEvent& e) override { for (TraceSink* c : consumers_) c->on_eviction(e); }
  void on_throttle(const ThrottleEvent& e) override { for (TraceSink* c : consumers_) c->on_throttle(e); }
  void on_memory(const MemoryEvent& e) override { for (TraceSink* c : consumers_) c->on_memory(e); }
  void on_cache_contents(const CacheContentsEvent& e) override { for (TraceSink* c : consumers_) c->on_cache_contents(e); }
  void on_end(double time) override { for (TraceSink* c : consumers_) c->on_end(time); }

 private:
  std::vector<TraceSink*> consumers_;
};

}  // namespace pagecache::workload
