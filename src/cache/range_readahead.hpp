#pragma once
// RangeReadahead: the kernel's on-demand readahead (mm/readahead.c) for one reader of a file by
// parts. A request that starts where the previous one ended (or at the file's start) is
// sequential: once it passes what was read ahead, the device reads the next window from there,
// the windows ramping up as storage::Readahead's; any other request is random and reads only
// its pages, and starts the ramp afresh. POSIX_FADV_RANDOM turns readahead off,
// POSIX_FADV_SEQUENTIAL doubles its largest window (as the kernel doubles ra_pages).

#include "cache/plan.hpp"

#include <pagecache/devices.hpp>
#include <pagecache/host.hpp>

#include "storage/readahead.hpp"

#include <cstdint>
#include <optional>

namespace pagecache::cache {

class RangeReadahead {
 public:
  RangeReadahead(const Disk& disk, ReadAdvice advice) noexcept
      : read_ahead_(advice == ReadAdvice::Random ? 0 : disk.read_ahead() * (advice == ReadAdvice::Sequential ? 2 : 1)),
        max_request_(disk.max_request()) {}

  /// What the device reads for a request of `pages` (the pages it touches) of a file of
  /// `size` bytes: the pages, or from them to the end of the next readahead window.
  ByteRange window(const ByteRange& pages, std::int64_t size) {
    const std::int64_t end = pages.offset + pages.length;
    const bool sequential = pages.offset == expected_;
    expected_ = end;
    if (read_ahead_ == 0 || !sequential) {
      ramp_.reset();
      ahead_to_ = 0;
      next_ = 0;
      return pages;
    }
    if (!ramp_) ramp_.emplace(read_ahead_, max_request_, pages.length);
    if (end <= ahead_to_) return pages;  // read ahead already (what eviction took is read again)
    const std::int64_t to = std::min(size, std::max(end, std::max(pages.offset, ahead_to_) + ramp_->window(next_++)));
    ahead_to_ = to;
    return {.offset = pages.offset, .length = to - pages.offset};
  }

 private:
  std::int64_t read_ahead_;
  std::int64_t max_request_;
  std::optional<storage::Readahead> ramp_;
  std::int64_t expected_ = 0;  // where a sequential request starts
  std::int64_t ahead_to_ = 0;  // the end of what was read ahead
  std::int64_t next_ = 0;      // the next window's number
};

}  // namespace pagecache::cache
