#pragma once
// Readahead: the windows in which the kernel reads a file that a process reads sequentially,
// and the device time they take when each window is one request paying a latency.
//
// It follows the on-demand readahead of mm/readahead.c (ondemand_readahead). A read() of r
// bytes at the start of the file opens the first window, get_init_ra_size(roundup_pow_of_two(r),
// max); each window the reader reaches then opens the next, get_next_ra_size(previous, max):
// x4 while small, x2 up to max, then max for good. max is the device's read_ahead_kb (ra_pages),
// raised for a read() larger than it to min(r, max_sectors_kb) as ractl_max_pages does (io_pages).
// The kernel counts in pages of 4 KiB: sizes are rounded down (read_ahead_kb, max_sectors_kb) or
// up (the read()) to pages. A window the block layer splits at max_sectors_kb pays one latency:
// its parts reach the device together.
//
// Pure arithmetic: no simulator, no cache. Windows double until max, so there are a few dozen at
// most before the steady state, whose cost is a closed form: seconds() is O(1) amortised.

#include <cstddef>
#include <cstdint>
#include <vector>

namespace pagecache::storage {

/// The kernel's page (x86-64), the unit of its readahead windows.
inline constexpr std::int64_t kReadaheadPage = 4096;

/// One sequential reader's readahead windows, from the start of its file.
class Readahead {
 public:
  /// `read_ahead`: the device's read_ahead_kb in bytes, at least a page; `max_request`: its
  /// max_sectors_kb in bytes, 0 (unlimited) or at least a page; `request`: the bytes of each
  /// read() (> 0). Throws ConfigError otherwise (a device with read_ahead 0 models none: make
  /// no Readahead for it).
  Readahead(std::int64_t read_ahead, std::int64_t max_request, std::int64_t request);

  /// Bytes of window `k` (0: the first), a whole number of pages.
  std::int64_t window(std::int64_t k) const noexcept;
  /// The window size the windows reach after a few steps and keep.
  std::int64_t max_window() const noexcept { return max_; }
  /// Bytes of the stream gone through seconds() so far.
  std::int64_t position() const noexcept { return position_; }

  /// The seconds the device spends on the next `bytes` of the stream, which it then passes: a
  /// window costs `latency` + window / `bandwidth`, and a window crossed in part the same share
  /// of that as of its bytes (each byte goes at its window's request rate,
  /// window / (latency + window / bandwidth)). For a chunk the device reads, bytes / seconds is
  /// the bound of that read (Disk::read's `bound`); with latency 0 it is the bandwidth, which
  /// the read has without a bound. `bandwidth` > 0, `latency` >= 0, `bytes` >= 0.
  double seconds(std::int64_t bytes, double latency, double bandwidth);

 private:
  std::vector<std::int64_t> ramp_;      // bytes of the windows below max_, in order
  std::vector<std::int64_t> ramp_end_;  // where each of them ends in the stream
  std::int64_t max_ = 0;
  std::int64_t position_ = 0;
  std::size_t current_ = 0;  // the ramp window holding position_; ramp_.size(): the steady state
};

}  // namespace pagecache::storage
