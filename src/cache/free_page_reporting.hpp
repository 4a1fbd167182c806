#pragma once
// FreePageReporting: which free memory a virtual machine's host has taken back (docs/model.md
// §6.16). With free page reporting (a virtio balloon), the guest reports free memory to the
// host, which reclaims it; the next write into such a page waits for the host to fault it in
// again. The kernel reports in passes at most PAGE_REPORTING_DELAY apart, each taking at most
// a sixteenth of the free memory (mm/page_reporting.c, page_reporting_cycle's budget), so a
// large free is reported over many seconds. Its allocator hands out unreported pages first
// (reported pages go back to the tail of the free lists).
//
// It watches the host's free memory and its applications' (anonymous) memory: a rise of free
// memory is memory freed now (warm), a fall takes warm memory first, newest first, then cold
// memory; passes, the first a delay after a free, report the oldest warm memory. Observing the
// balances rather than each operation makes memory freed and taken back within one operation
// (an eviction for a write) warm, as the pages are reused at once.
//
// With large folios (CacheSettings::large_folios), memory an application's buffer freed is
// single pages, which the page cache's multi-page allocations cannot use until they merge:
// buffers take it (first, newest first), the page cache takes memory the page cache freed and
// then cold memory, and buffer-freed memory only when nothing else is left.

#include <cstdint>
#include <deque>
#include <limits>

namespace pagecache::cache {

class FreePageReporting {
 public:
  /// `free`, `anonymous`: the free and application memory at time 0; `warm`: how much of the
  /// free memory was freed just before, by the page cache (the rest is cold); `delay`: seconds
  /// between reporting passes (0: freed memory is cold at once); `large_folios`: the page
  /// cache cannot take what buffers freed while other memory is left.
  FreePageReporting(std::int64_t free, std::int64_t anonymous, std::int64_t warm, double delay, bool large_folios);

  /// The free memory is `free` and the applications' memory `anonymous` at `now` (times never
  /// decrease); the rest of the change is the page cache's.
  void observe(std::int64_t free, std::int64_t anonymous, double now);
  /// The balances before the run starts (files cached at the start): neither freed nor taken
  /// by the run.
  void rebase(std::int64_t free, std::int64_t anonymous);
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
  /// Unreported memory, oldest first, and its total.
  struct Pool {
    std::deque<Freed> freed;
    std::int64_t bytes = 0;
    void add(double now, std::int64_t bytes);
    /// Takes up to `bytes`, newest first; returns what is still to take.
    std::int64_t take_newest(std::int64_t bytes);
  };
  /// The passes due by `now`.
  void report(double now);
  void drop_oldest(std::int64_t bytes);
  std::int64_t warm_bytes() const noexcept { return cache_freed_.bytes + buffer_freed_.bytes; }
  void freed(Pool& pool, std::int64_t bytes, double now);
  void taken_by_buffers(std::int64_t bytes);
  /// `free_before`: the free memory before this take.
  void taken_by_page_cache(std::int64_t bytes, std::int64_t free_before);

  Pool cache_freed_;   // freed by the page cache: any allocation takes it
  Pool buffer_freed_;  // freed by application buffers (cache_freed_ when not large_folios)
  std::int64_t free_ = 0;
  std::int64_t anonymous_ = 0;
  std::int64_t cold_taken_ = 0;
  double delay_;
  double next_pass_;
  bool large_folios_;
};

}  // namespace pagecache::cache
