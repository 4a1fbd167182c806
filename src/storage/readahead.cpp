#include "storage/readahead.hpp"

#include <pagecache/error.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <limits>

namespace pagecache::storage {

namespace {

std::int64_t roundup_pow_of_two(std::int64_t n) {
  std::int64_t p = 1;
  while (p < n) p <<= 1;
  return p;
}

// get_init_ra_size: the first window, in pages, for a read() of `pages`.
std::int64_t initial_window(std::int64_t pages, std::int64_t max) {
  const std::int64_t size = roundup_pow_of_two(pages);
  if (size <= max / 32) return 4 * size;
  if (size <= max / 4) return 2 * size;
  return max;
}

// get_next_ra_size: the window after one of `current` pages.
std::int64_t next_window(std::int64_t current, std::int64_t max) {
  if (current < max / 16) return 4 * current;
  if (current <= max / 2) return 2 * current;
  return max;
}

// ractl_max_pages: a read() larger than read_ahead_kb may have windows up to the device's
// largest request.
std::int64_t largest_window(std::int64_t ra_pages, std::int64_t io_pages, std::int64_t request_pages) {
  if (request_pages > ra_pages && io_pages > ra_pages) return std::min(request_pages, io_pages);
  return ra_pages;
}

}  // namespace

Readahead::Readahead(std::int64_t read_ahead, std::int64_t max_request, std::int64_t request) {
  if (read_ahead < kReadaheadPage) {
    throw ConfigError(fmt::format("readahead: read_ahead must be at least a page ({} bytes), got {}", kReadaheadPage, read_ahead));
  }
  if (max_request != 0 && max_request < kReadaheadPage) {
    throw ConfigError(fmt::format("readahead: max_request must be 0 (unlimited) or at least a page ({} bytes), got {}", kReadaheadPage,
                                  max_request));
  }
  if (request <= 0) throw ConfigError(fmt::format("readahead: a read() must be of at least 1 byte, got {}", request));
  const std::int64_t ra_pages = read_ahead / kReadaheadPage;
  const std::int64_t io_pages = max_request > 0 ? max_request / kReadaheadPage : std::numeric_limits<std::int64_t>::max();
  const std::int64_t request_pages = request / kReadaheadPage + (request % kReadaheadPage != 0 ? 1 : 0);
  const std::int64_t max = largest_window(ra_pages, io_pages, request_pages);
  // ondemand_readahead's merge of the next window into the first (readit) happens only when the
  // first is already max, and leaves it at max: the sizes below are the whole story.
  std::int64_t end = 0;
  for (std::int64_t w = initial_window(request_pages, max); w < max; w = next_window(w, max)) {
    ramp_.push_back(w * kReadaheadPage);
    end += w * kReadaheadPage;
    ramp_end_.push_back(end);
  }
  max_ = max * kReadaheadPage;
}

std::int64_t Readahead::window(std::int64_t k) const noexcept {
  return k >= 0 && static_cast<std::size_t>(k) < ramp_.size() ? ramp_[static_cast<std::size_t>(k)] : max_;
}

double Readahead::seconds(std::int64_t bytes, double latency, double bandwidth) {
  if (bytes < 0) throw SimulationError(fmt::format("readahead: negative size {} bytes", bytes));
  if (!(bandwidth > 0.0) || !(latency >= 0.0)) {
    throw SimulationError(fmt::format("readahead: bandwidth must be > 0 and latency >= 0, got {} B/s and {} s", bandwidth, latency));
  }
  const std::int64_t end = position_ + bytes;
  // The windows the bytes cross, each counted by the share of it they cover.
  double windows = 0.0;
  std::int64_t at = position_;
  while (current_ < ramp_.size() && at < end) {
    const std::int64_t stop = std::min(end, ramp_end_[current_]);
    windows += static_cast<double>(stop - at) / static_cast<double>(ramp_[current_]);
    at = stop;
    if (at == ramp_end_[current_]) ++current_;
  }
  if (at < end) windows += static_cast<double>(end - at) / static_cast<double>(max_);
  position_ = end;
  return static_cast<double>(bytes) / bandwidth + latency * windows;
}

}  // namespace pagecache::storage
