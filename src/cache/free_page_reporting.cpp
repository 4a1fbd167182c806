#include "cache/free_page_reporting.hpp"

#include <pagecache/error.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pagecache::cache {

FreePageReporting::FreePageReporting(std::int64_t free, std::int64_t warm, double delay)
    : free_(free), delay_(delay), next_pass_(kIdle) {
  if (!(delay >= 0.0) || !std::isfinite(delay)) throw ConfigError(fmt::format("page reporting delay must be >= 0 s, got {}", delay));
  warm = delay > 0.0 ? std::clamp<std::int64_t>(warm, 0, std::max<std::int64_t>(free, 0)) : 0;
  if (warm > 0) {
    warm_.push_back({0.0, warm});
    warm_bytes_ = warm;
    next_pass_ = delay;
  }
}

void FreePageReporting::drop_oldest(std::int64_t bytes) {
  while (bytes > 0 && !warm_.empty()) {
    const std::int64_t from = std::min(bytes, warm_.front().bytes);
    warm_.front().bytes -= from;
    warm_bytes_ -= from;
    bytes -= from;
    if (warm_.front().bytes == 0) warm_.pop_front();
  }
}

void FreePageReporting::report(double now) {
  // A pass that leaves warm memory asks for the next one a delay later; one that leaves none
  // goes idle until the next free (page_reporting_process). At most kPassShare + 1 passes.
  while (next_pass_ <= now) {
    drop_oldest((std::max<std::int64_t>(free_, 0) + kPassShare - 1) / kPassShare);
    next_pass_ = warm_bytes_ > 0 ? next_pass_ + delay_ : kIdle;
  }
}

void FreePageReporting::observe(std::int64_t free, double now) {
  report(now);
  const std::int64_t change = free - free_;
  free_ = free;
  if (change > 0) {
    if (delay_ <= 0.0) return;  // reported at once
    if (!warm_.empty() && warm_.back().time == now) warm_.back().bytes += change;
    else warm_.push_back({now, change});
    warm_bytes_ += change;
    if (next_pass_ == kIdle) next_pass_ = now + delay_;  // __page_reporting_request
    return;
  }
  std::int64_t taken = -change;
  while (taken > 0 && !warm_.empty()) {  // newest first
    const std::int64_t from = std::min(taken, warm_.back().bytes);
    warm_.back().bytes -= from;
    warm_bytes_ -= from;
    taken -= from;
    if (warm_.back().bytes == 0) warm_.pop_back();
  }
  cold_taken_ += taken;
}

void FreePageReporting::rebase(std::int64_t free) {
  free_ = free;
  drop_oldest(warm_bytes_ - std::max<std::int64_t>(free, 0));
}

std::int64_t FreePageReporting::warm(double now) {
  report(now);
  return warm_bytes_;
}

}  // namespace pagecache::cache
