#include "workload/access_pattern.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <limits>

namespace pagecache::workload {

namespace {

RequestPattern::Kind kind_of(AccessPattern pattern) {
  switch (pattern) {
    case AccessPattern::Random: return RequestPattern::Kind::Random;
    case AccessPattern::Strided: return RequestPattern::Kind::Strided;
    case AccessPattern::Ranges: return RequestPattern::Kind::Ranges;
    case AccessPattern::Sequential: break;
  }
  return RequestPattern::Kind::Sequential;
}

bool within(std::int64_t offset, std::int64_t length, std::int64_t size) { return offset >= 0 && length > 0 && offset <= size - length; }

}  // namespace

RequestPattern request_pattern(const AccessSpec& access) {
  RequestPattern p{.kind = kind_of(access.pattern),
                   .offset = access.offset,
                   .length = access.length,
                   .request = access.request,
                   .stride = access.stride,
                   .count = access.pattern == AccessPattern::Ranges ? 0 : access.count,
                   .replacement = access.replacement,
                   .seed = access.seed};
  p.ranges.reserve(access.ranges.size());
  for (const auto& [offset, length] : access.ranges) p.ranges.push_back({.offset = offset, .length = length});
  return p;
}

std::string pattern_problem(const RequestPattern& p, std::int64_t file_size) {
  if (p.request <= 0) return fmt::format("a request of {} bytes (must be > 0)", p.request);
  if (p.count < 0) return fmt::format("{} requests per epoch (must be >= 0)", p.count);
  if (p.kind == RequestPattern::Kind::Ranges) {
    if (p.ranges.empty()) return "no ranges";
    for (const ByteRange& r : p.ranges) {
      if (!within(r.offset, r.length, file_size)) {
        return fmt::format("the range of {} bytes at {} is not within the file ({} bytes)", r.length, r.offset, file_size);
      }
    }
    return {};
  }
  if (!within(p.offset, p.length, file_size)) {
    return fmt::format("the region of {} bytes at {} is not within the file ({} bytes)", p.length, p.offset, file_size);
  }
  const std::int64_t slots = (p.length + p.request - 1) / p.request;
  switch (p.kind) {
    case RequestPattern::Kind::Random:
      if (slots > std::numeric_limits<std::uint32_t>::max()) return fmt::format("{} requests to draw from (at most 2^32 - 1)", slots);
      if (!p.replacement && p.count > slots) return fmt::format("{} requests per epoch, more than the {} of the region", p.count, slots);
      break;
    case RequestPattern::Kind::Strided:
      if (p.stride < p.request) return fmt::format("a stride of {} bytes, shorter than a request ({})", p.stride, p.request);
      if (p.length < p.request) return fmt::format("a region of {} bytes, shorter than a request ({})", p.length, p.request);
      if (p.count > (p.length - p.request) / p.stride + 1) return fmt::format("{} requests per epoch, more than fit the region", p.count);
      break;
    default:
      break;
  }
  return {};
}

double bytes_per_epoch(const RequestPattern& p) {
  switch (p.kind) {
    case RequestPattern::Kind::Ranges: {
      double bytes = 0.0;
      for (const ByteRange& r : p.ranges) bytes += static_cast<double>(r.length);
      return bytes;
    }
    case RequestPattern::Kind::Strided:
      return static_cast<double>(RequestStream(p).per_epoch()) * static_cast<double>(p.request);
    default:
      // Every slot once: the region; else `count` requests (the last slot's shorter length aside).
      return p.count == 0 ? static_cast<double>(p.length) : static_cast<double>(p.count) * static_cast<double>(p.request);
  }
}

}  // namespace pagecache::workload
