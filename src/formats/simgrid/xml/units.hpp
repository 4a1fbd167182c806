#pragma once
// SimGrid's units for the values of platform XML, as SimGrid itself reads them
// (src/xbt/xbt_parse_units.cpp): a number directly followed by a unit, letter case significant.
//
// Bandwidth, in bytes/s: Bps, or bps for bits (1 Bps = 8 bps), each with the decimal prefixes
//   k M G T P E Z Y (steps of 10^3) or the binary ones Ki Mi Gi Ti Pi Ei Zi Yi (steps of 2^10):
//   "125MBps" = 1.25e8, "1Mbps" = 125000, "1MiBps" = 1048576. ("KBps" is no SimGrid unit.)
// Time, in s: w d h m s ms us ns ps.
// Speed, in flop/s: f with the decimal prefixes (kf ... Yf), or flops with the prefixes spelt
//   out (kiloflops ... yottaflops; SimGrid spells zetaflops with one t). No binary prefixes.
// Size, in bytes: B, or b for bits, with the prefixes of bandwidths ("268GB", "500GiB").
//
// A number without a unit is taken in the base unit (Bps, s, f, B), as SimGrid does while
// warning that unit-less values are deprecated: sg_lacks_unit says when to pass that warning
// on. Zero needs no unit. Spaces around the value are ignored; between number and unit they
// are not (SimGrid refuses "5 MBps" too). Negative, out-of-range or non-finite values (inf,
// nan, "1e308EBps"), hexadecimal numbers and unknown units throw ConfigError with a short
// message quoting the value; the caller adds the file, line, element and attribute.

#include <string_view>

namespace pagecache::formats::simgrid {

double parse_sg_bandwidth(std::string_view text);
double parse_sg_time(std::string_view text);
double parse_sg_speed(std::string_view text);
double parse_sg_size(std::string_view text);

/// Whether `text`, a value the parsers above accept, is a nonzero number without a unit
/// (SimGrid reads it in the base unit and warns).
bool sg_lacks_unit(std::string_view text);

}  // namespace pagecache::formats::simgrid
