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
DirtyThrottle::Domain DirtyThrottle::domain(DirtyLimit& limit, const DirtyLimits& limits, std::int64_t in_use) noexcept {
  if (in_use > limits.freerun) limit.update(sim_->now(), limits.thresh, in_use, throttled_ > 0);
  const std::int64_t hard = limit.hard_limit(limits.thresh);
  return Domain{.in_use = in_use, .limits = limits, .setpoint = (limits.freerun + hard) / 2, .hard_limit = hard};
}

double DirtyThrottle::Domain::pos_ratio() const noexcept {
  const double x = static_cast<double>(setpoint - in_use) / static_cast<double>(std::max<std::int64_t>(hard_limit - setpoint, 1));
  return std::clamp(1.0 + x * x * x, 0.0, 2.0);
}

DirtyThrottle::Step DirtyThrottle::Writer::next(std::int64_t remaining) {
  constexpr double kMaxPause = 1.0;
  // Memory is handed out in pages; slivers of free memory left by copies in flight are not
  // worth a copy: below this, the writer makes room first.
  constexpr std::int64_t kMinCopy = 4 * 1024 * 1024;
  DirtyThrottle& t = *throttle_;
  PageCache& cache = *t.cache_;
  // Copies in flight count: their pages are being dirtied.
  const Domain host = t.domain(t.limit_, dirty_limits(cache), dirty_and_writeback(cache) + cache.memory().reserved);
  bool free = host.runs_free(remaining);
  double pos_ratio = host.pos_ratio();
  // In a memory group the writer runs free only if both domains let it, and is paced by the
  // stricter of the two (balance_dirty_pages with a memcg domain, the kernel's cgroup writeback).
  if (group_ != kRootGroup) {
    if (t.group_limits_.size() <= group_) t.group_limits_.resize(static_cast<std::size_t>(group_) + 1);
    const Domain group = t.domain(t.group_limits_[group_], group_dirty_limits(cache, group_), cache.groups().dirty_and_writeback(group_));
    pos_ratio = std::min(pos_ratio, group.pos_ratio());
    free = free && group.runs_free(remaining);
  }
  if (free) {
    throttle(false);
  } else {
    throttle(true);
    t.flusher_->notify_dirty(group_);
    if (credit_ < static_cast<double>(remaining)) {
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
