#include "workload/request_pattern.hpp"

#include <algorithm>
#include <utility>

namespace pagecache::workload {

namespace {

constexpr auto mix = SplitMix64::mix;

}  // namespace

int permutation_half_bits(std::uint64_t n) noexcept {
  int half = 1;
  while (half < 32 && (std::uint64_t{1} << (2 * half)) < n) ++half;
  return half;
}

std::uint64_t permute(std::uint64_t index, std::uint64_t n, std::uint64_t key, int half_bits) noexcept {
  const std::uint64_t mask = (std::uint64_t{1} << half_bits) - 1;
  std::uint64_t x = index;
  do {
    std::uint64_t left = x >> half_bits;
    std::uint64_t right = x & mask;
    for (std::uint64_t round = 0; round < 4; ++round) {
      const std::uint64_t f = mix(key ^ (round * 0xD6E8FEB86659FD93ull) ^ (right * 0x9E3779B97F4A7C15ull)) & mask;
      left = std::exchange(right, left ^ f);
    }
    x = (left << half_bits) | right;
  } while (x >= n);  // cycle-walking: a permutation of the domain restricted to [0, n)
  return x;
}

RequestStream::RequestStream(RequestPattern pattern) : pattern_(std::move(pattern)) {
  const RequestPattern& p = pattern_;
  switch (p.kind) {
    case RequestPattern::Kind::Sequential:
    case RequestPattern::Kind::Random:
      slots_ = (p.length + p.request - 1) / p.request;
      per_epoch_ = p.count > 0 ? p.count : slots_;
      break;
    case RequestPattern::Kind::Strided: {
      const std::int64_t fit = p.length >= p.request ? (p.length - p.request) / p.stride + 1 : 0;
      per_epoch_ = p.count > 0 ? std::min(p.count, fit) : fit;
      break;
    }
    case RequestPattern::Kind::Ranges:
      for (const ByteRange& r : p.ranges) per_epoch_ += p.request > 0 ? (r.length + p.request - 1) / p.request : 1;
      break;
  }
  half_bits_ = permutation_half_bits(static_cast<std::uint64_t>(std::max<std::int64_t>(slots_, 1)));
  start_epoch(0);
}

void RequestStream::start_epoch(std::int64_t epoch) {
  index_ = 0;
  range_ = 0;
  within_ = 0;
  // Each epoch its own order: keys and draws from the seed and the epoch alone.
  key_ = mix(pattern_.seed ^ mix(static_cast<std::uint64_t>(epoch) + 0x5851F42D4C957F2Dull));
  draws_ = SplitMix64(key_);
}

ByteRange RequestStream::slot(std::int64_t i) const noexcept {
  const std::int64_t start = pattern_.offset + i * pattern_.request;
  return {.offset = start, .length = std::min(pattern_.request, pattern_.offset + pattern_.length - start)};
}

ByteRange RequestStream::request(std::int64_t i) {
  const RequestPattern& p = pattern_;
  switch (p.kind) {
    case RequestPattern::Kind::Sequential: return slot(i % slots_);
    case RequestPattern::Kind::Random: {
      const auto n = static_cast<std::uint64_t>(slots_);
      const std::uint64_t s =
          p.replacement ? draws_.below(static_cast<std::uint32_t>(n)) : permute(static_cast<std::uint64_t>(i) % n, n, key_, half_bits_);
      return slot(static_cast<std::int64_t>(s));
    }
    case RequestPattern::Kind::Strided: return {.offset = p.offset + i * p.stride, .length = p.request};
    case RequestPattern::Kind::Ranges: {
      const ByteRange& r = p.ranges[range_];
      const std::int64_t length = p.request > 0 ? std::min(p.request, r.length - within_) : r.length;
      const ByteRange out{.offset = r.offset + within_, .length = length};
      within_ += length;
      if (within_ == r.length) {
        ++range_;
        within_ = 0;
      }
      return out;
    }
  }
  return {};
}

bool RequestStream::next(ByteRange& out) {
  if (index_ == per_epoch_) return false;
  out = request(index_++);
  return true;
}

}  // namespace pagecache::workload
