#include "cache/free_page_reporting.hpp"

#include <pagecache/error.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pagecache::cache {

FreePageReporting::FreePageReporting(std::int64_t free, std::int64_t anonymous, std::int64_t warm, double delay, bool large_folios)
    : free_(free), anonymous_(anonymous), delay_(delay), next_pass_(kIdle), large_folios_(large_folios) {
  if (!(delay >= 0.0) || !std::isfinite(delay)) throw ConfigError(fmt::format("page reporting delay must be >= 0 s, got {}", delay));
  warm = delay > 0.0 ? std::clamp<std::int64_t>(warm, 0, std::max<std::int64_t>(free, 0)) : 0;
  if (warm > 0) {
    cache_freed_.add(0.0, warm);
    next_pass_ = delay;
  }
}

void FreePageReporting::Pool::add(double now, std::int64_t more) {
  if (!freed.empty() && freed.back().time == now) freed.back().bytes += more;
  else freed.push_back({now, more});
  bytes += more;
}

std::int64_t FreePageReporting::Pool::take_newest(std::int64_t wanted) {
  while (wanted > 0 && !freed.empty()) {
    const std::int64_t from = std::min(wanted, freed.back().bytes);
    freed.back().bytes -= from;
    bytes -= from;
    wanted -= from;
    if (freed.back().bytes == 0) freed.pop_back();
  }
  return wanted;
}

void FreePageReporting::drop_oldest(std::int64_t bytes) {
  while (bytes > 0 && warm_bytes() > 0) {
    // The older of the two pools' oldest frees (the page cache's on a tie).
    Pool& pool = buffer_freed_.freed.empty() || (!cache_freed_.freed.empty() && cache_freed_.freed.front().time <= buffer_freed_.freed.front().time)
                     ? cache_freed_
                     : buffer_freed_;
    Freed& oldest = pool.freed.front();
    const std::int64_t from = std::min(bytes, oldest.bytes);
    oldest.bytes -= from;
    pool.bytes -= from;
    bytes -= from;
    if (oldest.bytes == 0) pool.freed.pop_front();
  }
}

void FreePageReporting::report(double now) {
  // A pass that leaves warm memory asks for the next one a delay later; one that leaves none
  // goes idle until the next free (page_reporting_process). At most kPassShare + 1 passes.
  while (next_pass_ <= now) {
    drop_oldest((std::max<std::int64_t>(free_, 0) + kPassShare - 1) / kPassShare);
    next_pass_ = warm_bytes() > 0 ? next_pass_ + delay_ : kIdle;
  }
}

void FreePageReporting::freed(Pool& pool, std::int64_t bytes, double now) {
  if (bytes <= 0 || delay_ <= 0.0) return;  // nothing, or reported at once
  pool.add(now, bytes);
  if (next_pass_ == kIdle) next_pass_ = now + delay_;  // __page_reporting_request
}

void FreePageReporting::taken_by_buffers(std::int64_t bytes) {
  cold_taken_ += cache_freed_.take_newest(buffer_freed_.take_newest(bytes));
}

void FreePageReporting::taken_by_page_cache(std::int64_t bytes, std::int64_t free_before) {
  const std::int64_t cold_before = std::max<std::int64_t>(free_before - warm_bytes(), 0);
  const std::int64_t left = cache_freed_.take_newest(bytes);
  // Then cold memory, and what buffers freed only when no cold memory is left.
  const std::int64_t from_cold = std::min(left, cold_before);
  cold_taken_ += from_cold + buffer_freed_.take_newest(left - from_cold);
}

void FreePageReporting::observe(std::int64_t free, std::int64_t anonymous, double now) {
  report(now);
  // What the applications' and the page cache's memory did, frees first (memory freed and
  // taken in one operation is warm), then the page cache's pages, then the buffers they are
  // copied into.
  const std::int64_t buffers = anonymous - anonymous_;
  const std::int64_t cache = (free_ - free) - buffers;
  std::int64_t balance = free_;
  if (buffers < 0) freed(large_folios_ ? buffer_freed_ : cache_freed_, -buffers, now);
  if (cache < 0) freed(cache_freed_, -cache, now);
  balance += std::max<std::int64_t>(-buffers, 0) + std::max<std::int64_t>(-cache, 0);
  if (cache > 0) taken_by_page_cache(cache, balance);
  if (buffers > 0) taken_by_buffers(buffers);
  free_ = free;
  anonymous_ = anonymous;
}

void FreePageReporting::rebase(std::int64_t free, std::int64_t anonymous) {
  free_ = free;
  anonymous_ = anonymous;
  drop_oldest(warm_bytes() - std::max<std::int64_t>(free, 0));
}

std::int64_t FreePageReporting::warm(double now) {
  report(now);
  return warm_bytes();
}

}  // namespace pagecache::cache
