#pragma once
// An axis's `range = { from, to, step }` or `{ from, to, factor }` (a log range). Its length is
// computed before any value is made, so that a range of a billion values (a factor of
// 1.0000001, a step of 1e-9) is refused at once instead of after filling the memory.

#include "sweep/sweep.hpp"

#include <toml++/toml.h>

#include <string>
#include <vector>

namespace pagecache::sweep {

/// A float as TOML text that reads back as the same float: 12 significant digits drop the
/// residue of from + k * step (0.30000000000000004 is 0.3).
std::string float_text(double v);

struct Range {
  std::string key;
  double from = 0, to = 0, by = 0;
  bool log = false;       ///< by is a factor
  bool integers = false;  ///< from, to and by are integers: so are the values
  const toml::node* by_node = nullptr;  ///< the step or factor, for messages
  std::string file, where;
};

/// Reads and checks a range table of the axis `where` (e.g. "axis 'pipelines.count'"). Throws
/// ConfigError naming the file, line and axis: a key missing or unknown, a bound, step or
/// factor that is not a finite number ("step = nan is not a number"), a step of 0, a factor
/// of 1 or below 0, a range that never reaches its end.
Range read_range(const std::string& key, const toml::table& range, const std::string& file, const std::string& where);

/// How many values the range makes (of a log range of integers: its steps, some of which may
/// round to one value), computed, not counted. Throws ConfigError, naming the axis, if more
/// than `max_values`.
double range_length(const Range& range, double max_values);

/// The values, from `from` towards `to`. Call range_length first: this makes them all.
std::vector<Override> range_values(const Range& range);

}  // namespace pagecache::sweep
