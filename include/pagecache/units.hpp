#pragma once
// Human units at the edges: "3 GB", "3 GiB", "465 MB/s", "30 s", "250 ms".
//
// Sizes: B, kB/KB, MB, GB, TB, PB, EB (powers of 10) and KiB, MiB, GiB, TiB, PiB, EiB (powers
// of 2), or a bare number of bytes (rounded to a whole byte), at most 1 EiB. Bandwidths: a size
// per second ("465 MB/s"), bits per second ("10 Gbit/s", "100 Mbit/s"), or a bare number of
// bytes per second. Durations: ns, us, ms, s, min, h, or a bare number of seconds. Decimal and
// binary prefixes are never confused: "GB" is 10^9, "GiB" is 2^30. Negative and non-finite
// values are rejected. Errors throw ConfigError with a message saying what was expected, and
// for a unit in the wrong letter case or a common misspelling ("gib", "Gbps") the right one.

#include <cstdint>
#include <string>
#include <string_view>

namespace pagecache::units {

/// The largest size pcsim takes: 1 EiB, so that sums of a few sizes never overflow.
inline constexpr std::int64_t kMaxBytes = std::int64_t{1} << 60;
/// The longest duration pcsim takes (about 32 years): double-precision time keeps the
/// microsecond up to about there.
inline constexpr double kMaxSeconds = 1e9;
/// Bandwidths pcsim takes, bytes per second: from 1 B/s to 1 PB/s.
inline constexpr double kMinBandwidth = 1.0;
inline constexpr double kMaxBandwidth = 1e15;

std::int64_t parse_size(std::string_view text);
double parse_bandwidth(std::string_view text);
double parse_duration(std::string_view text);

/// Shortest exact rendering, for printing resolved scenarios: "3 GB", "3 GiB", "123 B".
std::string format_size(std::int64_t bytes);
std::string format_bandwidth(double bytes_per_second);
std::string format_duration(double seconds);
/// A moment of simulated time in a message ("t = 12.500000 s"): six decimals up to
/// kMaxSeconds, beyond it (a run that went astray) in scientific notation, never hundreds of
/// digits.
std::string format_instant(double seconds);

}  // namespace pagecache::units
