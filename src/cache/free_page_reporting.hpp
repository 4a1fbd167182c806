#pragma once
// FreePageReporting: which free memory a virtual machine's host has taken back (docs/model.md
// §6.16). With free page reporting (a virtio balloon), the guest reports free memory to the
// host, which reclaims it; the next write into such a page waits for the host to fault it in
// again. The kernel reports in passes at most PAGE_REPORTING_DELAY apart, each taking at most
// a sixteenth of the free memory (mm/page_reporting.c, page_reporting_cycle's budget), so a
// large free is reported over many seconds. Its allocator hands out unreported pages first
// (reported pages go back to the tail of the free lists).
//
// It watches the host's free memory: a rise is memory freed now (warm), a fall takes warm
// memory first, newest first, then cold memory; passes, the first a delay after a free, report
// the oldest warm memory. Observing the balance rather than each operation makes memory freed and taken
// back within one operation (an eviction for a write) warm, as the pages are reused at once.

#include <cstdint>
#include <deque>
#include <limits>

namespace pagecache::cache {

class FreePageReporting {
 public:
  /// `free`: the free memory at time 0; `warm`: how much of it was freed just before (the
  /// rest is cold); `delay`: seconds between reporting passes (0: freed memory is cold at once).
  FreePageReporting(std::int64_t free, std::int64_t warm, double delay);

  /// The free memory is `free` at `now` (times never decrease).
  void observe(std::int64_t free, double now);
  /// The free memory is `free` before the run starts (files cached at the start): neither
  /// freed nor taken by the run.
  void rebase(std::int64_t free);
  /// Bytes taken from cold memory so far: an operation's share is the difference across it.
  std::int64_t cold_taken() const noexcept { return cold_taken_; }
  /// Free memory not yet reported at `now` (for tests and checks).
  std::int64_t warm(double now);

  /// The fraction of the free memory one pass reports at most.
  static constexpr std::int64_t kPassShare = 16;
  static constexpr double kIdle = std::numeric_limits<double>::infinity();

 private:
  struct Freed {
    double time;
    std::int64_t bytes;
  };
  /// The passes due by `now`.
  void report(double now);
  void drop_oldest(std::int64_t bytes);

  std::deque<Freed> warm_;  // oldest first
  std::int64_t warm_bytes_ = 0;
  std::int64_t free_ = 0;
  std::int64_t cold_taken_ = 0;
  double delay_;
  double next_pass_;
};

}  // namespace pagecache::cache
