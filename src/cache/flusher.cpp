#include "cache/flusher.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace pagecache::cache {

void Flusher::start() {
  if (started_) return;
  started_ = true;
  sim_->spawn(periodic());
}

void Flusher::notify_dirty() {
  if (wake_ && !wake_->triggered()) wake_->trigger();
}

Task<void> Flusher::periodic() {
  const double interval = cache_->settings().writeback_interval;
  const double expire = cache_->settings().dirty_expire;
  double tick = sim_->now();
  for (;;) {
    if (sim_->now() < tick) {
      if (cache_->dirty() == 0) {
        wake_.emplace(*sim_);
        co_await wake_->wait();
        wake_.reset();
        // Back on the cadence: the first tick time at or after now.
        if (sim_->now() > tick) tick += std::ceil((sim_->now() - tick) / interval) * interval;
      }
      co_await sim_->sleep_until(tick);
    }
    const double cutoff = tick - expire;
    for (;;) {
      const PageCache::Flushed taken = cache_->flush_expired_block(cutoff);
      if (taken.bytes == 0) break;
      flushed_ += taken.bytes;
      co_await (*files_)[taken.file].disk->write(taken.bytes);
      cache_->end_writeback(taken);
    }
    // A tick that took longer than the interval is followed by the next one at once.
    tick = std::max(tick + interval, sim_->now());
  }
}

}  // namespace pagecache::cache
