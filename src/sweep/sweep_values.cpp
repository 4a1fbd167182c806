// The axes and points of a sweep file, read into overrides (sweep_values.hpp).
#include "sweep/sweep_values.hpp"

#include "scenario/toml_reader.hpp"

#include <pagecache/error.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <set>
#include <sstream>

namespace pagecache::sweep {

namespace {

using scenario::location;

// A value of an axis or a point as an override.
Override override_of(const std::string& key, const toml::node& value, const std::string& file, const std::string& where) {
  std::ostringstream text;
  std::string shown;
  if (const auto* s = value.as_string()) {
    shown = s->get();
    text << '"';  // a basic string: toml++ would write a literal one ('64 GB')
    for (const char c : shown) {
      const auto byte = static_cast<unsigned char>(c);
      if (c == '"' || c == '\\') text << '\\' << c;
      else if (byte < 0x20 || byte == 0x7f) text << fmt::format("\\u{:04X}", byte);
      else text << c;
    }
    text << '"';
  } else if (const auto* f = value.as_floating_point()) {
    text << float_text(f->get());  // toml++ writes 0.2 as 0.20000000000000001
    shown = text.str();
  } else if (value.is_integer() || value.is_boolean()) {
    value.visit([&](const auto& v) {
      if constexpr (toml::is_value<decltype(v)>) text << v;
    });
    shown = text.str();
  } else {
    fail_at(value, file, fmt::format("{}: a value is a string, a number or true/false", where));
  }
  return {key, text.str(), shown};
}

AxisShape read_axis(const toml::table& table, std::size_t index, const std::vector<AxisShape>& earlier, const std::string& path,
                    const SweepLimits& limits) {
  scenario::TomlReader a(table, fmt::format("axes[{}]", index), path);
  AxisShape axis;
  axis.key = a.required_string("key");
  const toml::node* values = a.raw("values");
  const toml::table* range = a.optional_table("range");
  a.finish();
  axis.name = fmt::format("axis '{}'", axis.key);
  for (const AxisShape& e : earlier)
    if (e.key == axis.key) a.fail("key", fmt::format("{} is swept twice", axis.name));
  if ((values == nullptr) == (range == nullptr)) a.fail_table(fmt::format("{}: give values = [...] or range = {{...}}, one of them", axis.name));
  if (values != nullptr) {
    axis.values = values->as_array();
    if (axis.values == nullptr) a.fail("values", fmt::format("{}: expected an array of values", axis.name));
    axis.length = static_cast<double>(axis.values->size());
    if (axis.length == 0) a.fail("values", fmt::format("{} has no value", axis.name));
    if (axis.length > limits.axis_values) {
      a.fail("values", fmt::format("{}: {} values, more than an axis may have ({:.0f})", axis.name, axis.values->size(), limits.axis_values));
    }
  } else {
    axis.range = read_range(axis.key, *range, path, axis.name);
    axis.length = range_length(*axis.range, limits.axis_values);
  }
  return axis;
}

}  // namespace

void fail_at(const toml::node& node, const std::string& file, const std::string& what) {
  throw ConfigError(fmt::format("{}: {}", location(node.source(), file), what));
}

std::vector<AxisShape> read_axes(const std::vector<const toml::table*>& axes, const std::string& path, const SweepLimits& limits) {
  std::vector<AxisShape> grid;
  for (std::size_t i = 0; i < axes.size(); ++i) grid.push_back(read_axis(*axes[i], i, grid, path, limits));
  return grid;
}

void check_run_count(const std::vector<AxisShape>& grid, std::size_t points, bool force, const SweepLimits& limits, const std::string& path) {
  double runs = 1.0;
  for (const AxisShape& axis : grid) runs *= axis.length;
  if (points > 0) runs = static_cast<double>(points);
  const double allowed = force ? kMaxNumberedRuns : limits.runs;
  if (runs > allowed) {
    if (runs > kMaxNumberedRuns) throw ConfigError(fmt::format("{}: {:.3g} runs, more than pcsim can number", path, runs));
    std::string shape;
    for (std::size_t i = 0; i < grid.size(); ++i) shape += fmt::format("{}{} {:.0f}", i ? " x " : "", grid[i].name, grid[i].length);
    if (shape.empty()) shape = "points";
    throw ConfigError(fmt::format("{}: {:.0f} runs ({}), more than {:.0f}: give --force to sweep them all", path, runs, shape, allowed));
  }
}

std::vector<Override> axis_values(const AxisShape& axis, const toml::table& table, std::size_t index, const std::string& path) {
  std::vector<Override> list;
  if (axis.values != nullptr) {
    list.reserve(axis.values->size());
    for (const toml::node& v : *axis.values) list.push_back(override_of(axis.key, v, path, axis.name));
  } else {
    list = range_values(*axis.range);
  }
  std::set<std::string> seen;
  for (const Override& o : list) {
    if (!seen.insert(o.toml).second) {
      scenario::TomlReader(table, fmt::format("axes[{}]", index), path)
          .fail(axis.values != nullptr ? "values" : "range", fmt::format("{}: the value {} is there twice", axis.name, o.toml));
    }
  }
  return list;
}

std::vector<std::vector<Override>> read_points(const std::vector<const toml::table*>& points, std::vector<std::string>& keys, const std::string& path) {
  // A point leaves unset what it does not name.
  std::vector<std::vector<Override>> rows;
  for (std::size_t i = 0; i < points.size(); ++i) {
    std::vector<Override> row(keys.size());
    for (const auto& [k, v] : *points[i]) {
      const std::string key(k.str());
      auto at = std::find(keys.begin(), keys.end(), key);
      if (at == keys.end()) {
        keys.push_back(key);
        for (auto& earlier : rows) earlier.emplace_back();
        row.emplace_back();
        at = keys.end() - 1;
      }
      row[static_cast<std::size_t>(at - keys.begin())] = override_of(key, v, path, fmt::format("points[{}], key '{}'", i, key));
    }
    rows.push_back(std::move(row));
  }
  std::set<std::string> ids;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (!ids.insert(run_id(rows[i])).second) fail_at(*points[i], path, fmt::format("points[{}] is the same run as an earlier point", i));
  }
  return rows;
}

}  // namespace pagecache::sweep
