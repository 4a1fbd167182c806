#pragma once
// RunTrace: where a run reports what happens. The recorder of its RunResult, and the run
// options' consumers beside it: the runner reports to all (phases, memory rows, cache contents);
// the devices and page caches only to the options' consumers, so that with none they report
// nothing.

#include "workload/platform.hpp"
#include "workload/result_recorder.hpp"

#include <pagecache/fair_share.hpp>
#include <pagecache/host.hpp>
#include <pagecache/run.hpp>
#include <pagecache/trace.hpp>

#include <cstddef>
#include <cstdint>
#include <deque>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace pagecache::workload {

/// What a phase moved: its files' IoResults summed, without their times.
struct Moved {
  std::int64_t bytes = 0;
  std::int64_t cache_bytes = 0;
  std::int64_t disk_bytes = 0;
};

inline void add_moved(Moved& sum, const IoResult& r) {
  sum.bytes += r.bytes;
  sum.cache_bytes += r.cache_bytes;
  sum.disk_bytes += r.disk_bytes;
}

class RunTrace {
 public:
  /// Attaches the recorder and `options`' consumers to the devices of `share` and `platform`
  /// and reports the start, for a run of `rows` timeline rows, `io_phases` of them I/O phases
  /// (the recorder's rows are reserved).
  RunTrace(const RunOptions& options, FairShare& share, const Platform& platform, std::size_t rows, std::size_t io_phases);
  RunTrace(const RunTrace&) = delete;
  RunTrace& operator=(const RunTrace&) = delete;

  TraceSink& sink() noexcept { return *sink_; }
  RunResult& result() noexcept { return recorder_.result(); }

  /// A phase that has just ended, with what it moved: its row.
  std::uint32_t report_phase(std::string_view app, std::string_view task, const Host& host, PhaseKind kind, double start, double end,
                             const Moved& moved);
  /// Every file's cached bytes, after the I/O phase of row `phase` (if they are recorded).
  void record_cache(std::uint32_t phase) {
    if (record_cache_) record_cache_contents(phase);
  }

 private:
  void record_cache_contents(std::uint32_t phase);
  RunTrace(const RunOptions& options, FairShare& share, const Platform& platform, std::size_t rows, std::size_t io_phases,
           std::string not_recorded);

  const Platform& platform_;
  bool record_cache_;
  ResultRecorder recorder_;
  std::deque<TraceFanout> fanouts_;
  TraceSink* sink_ = nullptr;                                  // the recorder, and the consumers
  std::unordered_map<const Host*, std::uint32_t> host_index_;  // in Platform::hosts()
  std::uint32_t phases_ = 0;                                   // ended so far
  std::vector<std::int64_t> cached_;                           // per file, after a phase: record_cache's buffer
};

}  // namespace pagecache::workload
