#pragma once
// MemoryProfile: the run's memory rows, a row per host whenever its memory differs from its
// previous row: at every change (memory_sample_interval 0), or at the ticks of the interval.

#include <pagecache/host.hpp>
#include <pagecache/memory_state.hpp>
#include <pagecache/simulator.hpp>
#include <pagecache/task.hpp>
#include <pagecache/trace.hpp>

#include <cstddef>
#include <optional>
#include <vector>

namespace pagecache::workload {

class MemoryProfile {
 public:
  /// The profile of `hosts` (which must outlive it), sampled every `interval` seconds (0: at
  /// every change).
  MemoryProfile(Simulator& sim, const std::vector<Host*>& hosts, double interval);
  MemoryProfile(const MemoryProfile&) = delete;
  MemoryProfile& operator=(const MemoryProfile&) = delete;

  /// Starts recording to `sink`, from the hosts' memory now; sampling ends once `running`
  /// (the tasks not yet ended, which must outlive the run) is 0.
  void start(TraceSink& sink, const int& running);
  /// A row for each host whose memory changed since its last row. True if any got one.
  bool record_all();

 private:
  bool record(double now, std::size_t host, const MemoryState& m);
  Task<void> sample(const int* running);
  Task<void> wait_for_change();

  Simulator& sim_;
  const std::vector<Host*>& hosts_;
  double interval_;
  TraceSink* sink_ = nullptr;
  std::vector<std::optional<MemoryState>> last_;  // per host, its last row
};

}  // namespace pagecache::workload
