#pragma once
// DirtyLimit: the global writeback domain's dirty limit (mm/page-writeback.c, struct
// wb_domain, dirty_limit), which sets where throttled writers are held.
//
// The dirty threshold (dirty_ratio x dirtyable memory) falls as soon as applications take
// memory; the kernel does not throttle writers to it at once. It keeps a limit that is set to
// the threshold when the machine starts or the sysctl is written (writeback_set_ratelimit),
// and afterwards moves only while writers are throttled: up to the threshold at once, down
// toward max(threshold, dirty) by 1/32 of the gap per 200 ms (update_dirty_limit, called
// from balance_dirty_pages at most every BANDWIDTH_INTERVAL). Writers are throttled around
// the setpoint halfway between the freerun ceiling and max(threshold, limit)
// (wb_position_ratio), so for a few seconds after memory was taken they may dirty more than
// the current threshold alone allows.

#include <algorithm>
#include <cstdint>
#include <limits>

namespace pagecache::cache {

class DirtyLimit {
 public:
  /// BANDWIDTH_INTERVAL: the limit moves at most once per this many seconds.
  static constexpr double kInterval = 0.2;

  /// The machine at rest: the limit is the threshold (writeback_set_ratelimit).
  void reset(std::int64_t thresh) noexcept {
    limit_ = thresh;
    stamp_ = -std::numeric_limits<double>::infinity();
  }
  /// A writer is in the throttled range (dirty above the freerun ceiling) at `now`. The kernel
  /// updates the limit at most once per interval, from balance_dirty_pages, which throttled
  /// writers call after every pause (200 ms at most): `waited_throughout` says writers were
  /// held all along since the last call, so one update per interval elapsed is due; otherwise
  /// (writers ran free, or none wrote) one update at most.
  void update(double now, std::int64_t thresh, std::int64_t dirty, bool waited_throughout) noexcept {
    if (now < stamp_ + kInterval) return;
    int steps = 1;
    if (waited_throughout) {
      steps = static_cast<int>((now - stamp_) / kInterval);
      stamp_ += steps * kInterval;
    } else {
      stamp_ = now;
    }
    for (; steps > 0; --steps) {
      if (limit_ < thresh) {
        limit_ = thresh;  // follow up in one step
        continue;
      }
      const std::int64_t target = std::max(thresh, dirty);
      if (limit_ > target) limit_ -= (limit_ - target) / 32;  // follow down slowly
      else break;
    }
  }
  /// hard_dirty_limit: what the setpoint is computed from.
  std::int64_t hard_limit(std::int64_t thresh) const noexcept { return std::max(thresh, limit_); }
  std::int64_t limit() const noexcept { return limit_; }

 private:
  std::int64_t limit_ = 0;
  double stamp_ = -std::numeric_limits<double>::infinity();
};

}  // namespace pagecache::cache
