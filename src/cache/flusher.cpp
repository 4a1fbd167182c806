#include "cache/flusher.hpp"

#include "cache/plan.hpp"

#include <cmath>
#include <limits>

namespace pagecache::cache {

void Flusher::start() {
  if (started_) return;
  started_ = true;
  sim_->spawn(periodic());
}

bool Flusher::background_due() const {
  if (!cache_->policy().background_writeback() || cache_->memory().dirty == 0) return false;
  return dirty_and_writeback(*cache_) > dirty_limits(*cache_).background;
}

bool Flusher::group_background_due(GroupId group) const {
  return cache_->groups().dirty_and_writeback(group) > group_dirty_limits(*cache_, group).background;
}

void Flusher::notify_dirty(GroupId group) {
  // A group over its own background threshold waits in due_groups_ (each once): the
  // flusher never scans every group, of which a workflow may have thousands.
  if (group != kRootGroup && cache_->policy().background_writeback() && group_background_due(group)) {
    if (group >= queued_.size()) queued_.resize(static_cast<std::size_t>(group) + 1, false);
    if (!queued_[group]) {
      queued_[group] = true;
      due_groups_.push_back(group);
    }
  }
  if (wake_ && !wake_->triggered() && (parked_ || background_due() || !due_groups_.empty())) wake_->trigger();
}

Task<std::int64_t> Flusher::write_group(GroupId group) {
  std::vector<PageCache::Flushed> taken;
  const std::int64_t total =
      cache_->flush(cache_->groups().dirty_and_writeback(group) - group_dirty_limits(*cache_, group).background, kNoFile, taken, group);
  for (const PageCache::Flushed& part : taken) {
    flushed_ += part.bytes;
    cache_->listeners().tracer.flush(FlushCause::Background, part.bytes);
    co_await (*files_)[part.file].disk->write(part.bytes);
    cache_->end_writeback(part);
  }
  co_return total;
}

Task<void> Flusher::write_block(double cutoff) {
  const PageCache::Flushed taken = cache_->flush_expired_block(cutoff);
  if (taken.bytes == 0) co_return;
  flushed_ += taken.bytes;
  cache_->listeners().tracer.flush(std::isinf(cutoff) ? FlushCause::Background : FlushCause::Expiry, taken.bytes);
  co_await (*files_)[taken.file].disk->write(taken.bytes);
  cache_->end_writeback(taken);
}

Task<void> Flusher::periodic() {
  const double interval = cache_->settings().writeback_interval;
  const double expire = cache_->settings().dirty_expire;
  constexpr double kAnyAge = std::numeric_limits<double>::infinity();
  double tick = sim_->now();
  for (;;) {
    if (background_due()) {
      // Background writeback: the oldest dirty data, one block at a time, until the dirty
      // data is back under the background threshold.
      co_await write_block(kAnyAge);
      continue;
    }
    // Groups over their own background thresholds, in the order they got there; one whose
    // data is all in writeback already is dropped until its writers dirty more.
    if (!due_groups_.empty()) {
      const GroupId group = due_groups_.front();
      due_groups_.pop_front();
      queued_[group] = false;
      // Still over after writing some: back in the queue.
      if (group_background_due(group) && co_await write_group(group) > 0) notify_dirty(group);
      continue;
    }
    if (sim_->now() >= tick) {
      // Periodic writeback of the data dirty for longer than dirty_expire at the tick.
      const double cutoff = tick - expire;
      while (cache_->memory().dirty > 0) {
        const std::int64_t before = flushed_;
        co_await write_block(cutoff);
        if (flushed_ == before) break;
      }
      // Each group's writeback work also wakes at the interval and looks at its background
      // threshold (wb_workfn, wb_check_background_flush), which may have fallen under its
      // dirty data as memory was taken: once per tick, not per write.
      for (std::size_t g = 1; g < cache_->groups().size(); ++g) notify_dirty(static_cast<GroupId>(g));
      // A tick that took longer than the interval is followed by the next one at once.
      tick = std::max(tick + interval, sim_->now());
      continue;
    }
    // Idle until the next tick, or, with no dirty data at all, until some appears; background
    // writeback becoming due wakes it early.
    parked_ = cache_->memory().dirty == 0;
    wake_.emplace(*sim_);
    if (parked_) co_await wake_->wait();
    else co_await wake_->wait_for(tick - sim_->now());
    wake_.reset();
    parked_ = false;
    // Back on the cadence: the first tick time at or after now.
    if (sim_->now() > tick) tick += std::ceil((sim_->now() - tick) / interval) * interval;
  }
}

}  // namespace pagecache::cache
