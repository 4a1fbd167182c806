#pragma once
// The values of a sweep file (sweep.hpp): its [[axes]], each one's length known before any of
// its values is made, then their values; or its [[points]]. Each value as an override.

#include "sweep/sweep.hpp"
#include "sweep/range.hpp"

#include <toml++/toml.h>

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace pagecache::sweep {

/// A ConfigError at `node` of the sweep file `file`.
[[noreturn]] void fail_at(const toml::node& node, const std::string& file, const std::string& what);

/// An axis as read, before its values are made.
struct AxisShape {
  std::string key, name;
  const toml::array* values = nullptr;  ///< values = [...], or
  std::optional<Range> range;           ///< range = {...}
  double length = 0;
};

/// Each axis's key and length, no value made: a range of 10^9 values is refused at once, not
/// once it has filled the memory. ConfigError for a key swept twice, neither or both of values
/// and range, an axis without a value or longer than `limits.axis_values`.
std::vector<AxisShape> read_axes(const std::vector<const toml::table*>& axes, const std::string& path, const SweepLimits& limits);

/// ConfigError if the grid (or the `points`) makes more runs than pcsim numbers, or than
/// `limits.runs` without `force`.
void check_run_count(const std::vector<AxisShape>& grid, std::size_t points, bool force, const SweepLimits& limits, const std::string& path);

/// The values of the axis read from `table`, the `index`th; ConfigError for a value there twice.
std::vector<Override> axis_values(const AxisShape& axis, const toml::table& table, std::size_t index, const std::string& path);

/// The points, each a value per key of `keys` ("" toml: not set), `keys` extended in the order
/// keys first appear; ConfigError for a point that is the same run as an earlier one.
std::vector<std::vector<Override>> read_points(const std::vector<const toml::table*>& points, std::vector<std::string>& keys, const std::string& path);

}  // namespace pagecache::sweep
