#include "cache/dirty_throttle.hpp"

#include <algorithm>

namespace pagecache::cache {

DirtyThrottle::Writer::~Writer() { throttle(false); }

void DirtyThrottle::Writer::throttle(bool on) noexcept {
  if (on != throttled_) throttle_->throttled_ += on ? 1 : -1;
  throttled_ = on;
}

// balance_dirty_pages (mm/page-writeback.c): the writer never writes back itself.
// - Dirty + writeback under the setpoint (halfway between the freerun ceiling and the
//   domain's limit, see DirtyLimit): it dirties pages at memory speed. (The kernel lets it
//   run free under the freerun ceiling only, and paces it by its rate limit above; while
//   that rate limit is adapted to the device, which it is in a steady state, the two meet
//   at the setpoint.)
// - Above the setpoint: its rate is the device's write bandwidth shared by the throttled
//   writers, times the kernel's position ratio 1 + ((setpoint - dirty) / (limit -
//   setpoint))^3 (pos_ratio_polynom), which is 1 at the setpoint and 0 at the limit: the
//   writers together dirty data as fast as writeback cleans it when dirty sits at the
//   setpoint, slower above it. The kernel pauses a writer every few pages, 200 ms at most
//   (MAX_PAUSE); pcsim paces it per chunk, the model's unit of I/O: the writer pauses
//   until it has earned the chunk at that rate, looking again at least every second, then
//   writes it.
DirtyThrottle::Step DirtyThrottle::Writer::next(std::int64_t remaining) {
  constexpr double kMaxPause = 1.0;
  // Memory is handed out in pages; slivers of free memory left by copies in flight are not
  // worth a copy: below this, the writer makes room first.
  constexpr std::int64_t kMinCopy = 4 * 1024 * 1024;
  DirtyThrottle& t = *throttle_;
  PageCache& cache = *t.cache_;
  // Copies in flight count: their pages are being dirtied.
  const std::int64_t in_use = cache.dirty_and_writeback() + cache.reserved();
  const DirtyLimits limits = dirty_limits(cache);
  if (in_use > limits.freerun) t.limit_.update(t.sim_->now(), limits.thresh, in_use, t.throttled_ > 0);
  const std::int64_t limit = t.limit_.hard_limit(limits.thresh);
  const std::int64_t setpoint = (limits.freerun + limit) / 2;
  // Under the background threshold nothing would write back to pace the writer by: it goes
  // on (a setpoint within a chunk of it only happens on tiny memories).
  if (in_use + remaining <= setpoint || in_use <= limits.background) {
    throttle(false);
  } else {
    throttle(true);
    t.flusher_->notify_dirty();
    if (credit_ < static_cast<double>(remaining)) {
      const double x = static_cast<double>(setpoint - in_use) / static_cast<double>(std::max<std::int64_t>(limit - setpoint, 1));
      const double pos_ratio = std::clamp(1.0 + x * x * x, 0.0, 2.0);
      const double rate = device_bw_ * pos_ratio / static_cast<double>(t.throttled_);
      const double pause = rate > 0.0 ? std::min(kMaxPause, (static_cast<double>(remaining) - credit_) / rate) : kMaxPause;
      return {Step::Pause, 0, pause, rate};
    }
  }
  // Reclaim knows pages, not files: the file's own older clean pages may go too (with
  // protect_files_being_written, only once no other clean data is left).
  cache.evict(remaining - cache.free(), kNoFile);
  const std::int64_t to_cache = std::min(remaining, cache.free());
  if (to_cache < std::min(remaining, kMinCopy)) return {Step::MakeRoom, 0, 0.0, 0.0};
  if (throttled_) credit_ -= static_cast<double>(to_cache);
  // As a copy into the cache: the pages are taken now and hold the data (dirty, entry time
  // the end of the copy) once the copy is done.
  cache.reserve(to_cache);
  return {Step::Copy, to_cache, 0.0, 0.0};
}

}  // namespace pagecache::cache
