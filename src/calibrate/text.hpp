#pragma once
// How calibrate writes sizes and rates in its notes and its platform file: binary sizes (the
// kernel's units), rates in MB/s (the platform's).

#include <fmt/format.h>

#include <cstdint>
#include <string>

namespace pagecache::calibrate {

inline constexpr std::int64_t MiB = 1 << 20;
inline constexpr std::int64_t GiB = 1LL << 30;

inline std::string size_text(std::int64_t bytes) {
  if (bytes >= GiB) return fmt::format("{:.1f} GiB", static_cast<double>(bytes) / GiB);
  return fmt::format("{} MiB", bytes / MiB);
}

inline std::string rate_text(double bytes_per_s) { return fmt::format("{:.0f} MB/s", bytes_per_s / 1e6); }

}  // namespace pagecache::calibrate
