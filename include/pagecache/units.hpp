#pragma once
// Human units at the edges: "3 GB", "3 GiB", "465 MB/s", "30 s", "250 ms".
//
// Sizes: B, kB/KB, MB, GB, TB (powers of 10) and KiB, MiB, GiB, TiB (powers of 2), or a bare
// number of bytes. Bandwidths: a size per second ("465 MB/s"), or a bare number of bytes per
// second. Durations: ns, us, ms, s, min, h, or a bare number of seconds. Decimal and binary
// prefixes are never confused: "GB" is 10^9, "GiB" is 2^30. Negative values are rejected.
// Errors throw ConfigError with a message saying what was expected.

#include <cstdint>
#include <string>
#include <string_view>

namespace pagecache::units {

std::int64_t parse_size(std::string_view text);
double parse_bandwidth(std::string_view text);
double parse_duration(std::string_view text);

/// Shortest exact rendering, for printing resolved scenarios: "3 GB", "3 GiB", "123 B".
std::string format_size(std::int64_t bytes);
std::string format_bandwidth(double bytes_per_second);
std::string format_duration(double seconds);

}  // namespace pagecache::units
