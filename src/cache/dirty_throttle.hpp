#pragma once
// DirtyThrottle: dirty throttling as the kernel's balance_dirty_pages does it, for one host.
// It holds what the writers share (how many are throttled, the dirty limit that moves while
// they are); each writer's chunk is a Writer, which says what the writer does next: pause,
// make room, or copy into the cache. The I/O controller carries the steps out.

#include "cache/dirty_limit.hpp"
#include "cache/flusher.hpp"
#include "cache/page_cache.hpp"
#include "cache/plan.hpp"

#include <pagecache/simulator.hpp>

#include <cstdint>

namespace pagecache::cache {

class DirtyThrottle {
 public:
  DirtyThrottle(const Simulator& sim, PageCache& cache, Flusher& flusher) noexcept : sim_(&sim), cache_(&cache), flusher_(&flusher) {}

  /// The machine at rest: the dirty limit back at the threshold (DirtyLimit::reset).
  void at_rest() { limit_.reset(dirty_limits(*cache_).thresh); }

  /// What a writer does next: pause for `pause` seconds, earning `rate` bytes a second; make
  /// room by writing back; or copy `to_cache` bytes, whose pages it has reserved.
  struct Step {
    enum Kind : std::uint8_t { Pause, MakeRoom, Copy } kind;
    std::int64_t to_cache;
    double pause;
    double rate;
  };

  /// One writer's chunk, from its first step to its last copy. Leaves the throttled writers
  /// when it ends.
  class Writer {
   public:
    /// `device_bw`: the write bandwidth of the file's device, which the throttled writers share.
    Writer(DirtyThrottle& throttle, double device_bw) noexcept : throttle_(&throttle), device_bw_(device_bw) {}
    ~Writer();
    Writer(const Writer&) = delete;
    Writer& operator=(const Writer&) = delete;

    /// The next step with `remaining` bytes of the chunk still to write.
    Step next(std::int64_t remaining);
    /// The pause `step` asked for is over: its bytes are earned.
    void paused(const Step& step) noexcept { credit_ += step.rate * step.pause; }

   private:
    void throttle(bool on) noexcept;

    DirtyThrottle* throttle_;
    double device_bw_;
    double credit_ = 0.0;  // bytes this writer's pauses have earned for this chunk
    bool throttled_ = false;
  };

 private:
  const Simulator* sim_;
  PageCache* cache_;
  Flusher* flusher_;
  std::int64_t throttled_ = 0;  // writers held now
  DirtyLimit limit_;
};

}  // namespace pagecache::cache
