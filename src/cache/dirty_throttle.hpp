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
#include <vector>

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
    /// `group`: the memory group the file is charged to, whose own dirty limits hold too.
    Writer(DirtyThrottle& throttle, double device_bw, GroupId group = kRootGroup) noexcept
        : throttle_(&throttle), device_bw_(device_bw), group_(group) {}
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
    GroupId group_;
    double credit_ = 0.0;  // bytes this writer's pauses have earned for this chunk
    bool throttled_ = false;
  };

 private:
  /// A writeback domain as one writer sees it: the host's, or its memory group's.
  struct Domain {
    std::int64_t in_use;      // dirty + writeback (+ copies in flight, for the host)
    DirtyLimits limits;
    std::int64_t setpoint;    // halfway between the freerun ceiling and the hard limit
    std::int64_t hard_limit;
    /// Writing `remaining` more keeps the writer free of this domain's throttling.
    bool runs_free(std::int64_t remaining) const noexcept { return in_use + remaining <= setpoint || in_use <= limits.background; }
    /// The kernel's position ratio (pos_ratio_polynom), 1 at the setpoint and 0 at the limit.
    double pos_ratio() const noexcept;
  };
  /// The domain of `limits` with `in_use` bytes, its dirty limit `limit` moved first.
  Domain domain(DirtyLimit& limit, const DirtyLimits& limits, std::int64_t in_use) noexcept;

  const Simulator* sim_;
  PageCache* cache_;
  Flusher* flusher_;
  std::int64_t throttled_ = 0;  // writers held now
  DirtyLimit limit_;
  std::vector<DirtyLimit> group_limits_;  // by GroupId, made when a group's writer first asks
};

}  // namespace pagecache::cache
