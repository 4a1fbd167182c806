#pragma once
// fio's option values (fio 3.33, parse.c): integers with size suffixes under kb_base, times
// with each option's default unit, 0/1 booleans, bare set-type flags, the R,W[,T] split of
// per-direction options, and ':' lists with '\:' escapes. Each parser throws ConfigError naming
// the option where fio would silently read something else (see formats/fio/job_file.hpp).

#include "formats/fio/syntax.hpp"

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace pagecache::formats::fio {

/// How messages name an option: "option 'KEY=VALUE'", or "option 'KEY'" for one of an included
/// file (its values are never quoted), or "an option line" for a key that is no option's name.
std::string label(const RawOption& option);

/// A value's text as messages show it: quoted, or "its value" for an included file's.
std::string shown_value(const RawOption& option, std::string_view text);

/// A size that may be a percentage (size, offset, offset_increment, io_size).
struct SizeOrPercent {
  std::int64_t bytes = 0;
  int percent = 0;  ///< 1..100 when written "N%", else 0
};

/// A size in bytes: digits (or 0x and hex digits), then b, k, kb, ki, kib ... p, pb, pi, pib in
/// any case. With kb_base=1024, k is 1024 and kib 1000 (fio's inverted rule); kb_base=1000 swaps
/// them. Negative values only if `allow_negative`.
std::int64_t parse_size(const RawOption& option, std::string_view text, int kb_base, bool allow_negative = false);

/// parse_size, or "N%" with N in 1..100.
SizeOrPercent parse_size_or_percent(const RawOption& option, std::string_view text, int kb_base);

/// An integer option (numjobs, nrfiles, loops, ...): fio reads it as a size, so 1k is 1024;
/// refused outside [min, max].
std::int64_t parse_count(const RawOption& option, int kb_base, std::int64_t min, std::int64_t max);

/// A time in seconds: digits, then us/usec, ms/msec, s, m (minutes), h or d; without a suffix
/// the option's unit `default_seconds` (1 for runtime, 1e-6 for thinktime).
double parse_time(const RawOption& option, double default_seconds);

/// A bool option: exactly 0 or 1 (fio refuses a bare bool option, and true/yes).
bool parse_bool(const RawOption& option);

/// A set-type flag (time_based, stonewall, ...): bare means 1, else an unsigned integer, non-zero
/// being true.
bool parse_flag(const RawOption& option);

/// The pieces of a per-direction value as fio splits it (parse.c handle_option): on ',' if
/// there is one, else on ':', else on '-'. A trailing ',' leaves an empty last piece: fio then
/// keeps the later directions' sizes instead of copying the last one to them.
std::vector<std::string> split_directions(std::string_view value);

/// A ':' separated list of names (filename=, directory=): "\:" is a literal ':', empty entries
/// are skipped, the whole value's surrounding blanks are dropped.
std::vector<std::string> split_names(std::string_view value);

/// Refuses a value that is empty, or holds ',' ':' or '-' where fio would read a second value
/// and silently drop it (size=4k-8k is 4k).
void require_single_value(const RawOption& option);

}  // namespace pagecache::formats::fio
