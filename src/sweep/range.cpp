#include "sweep/range.hpp"

#include "scenario/toml_reader.hpp"

#include <pagecache/error.hpp>

#include <fmt/format.h>

#include <cmath>
#include <cstdint>

namespace pagecache::sweep {

namespace {

// Both the step count and the last value allow for the rounding of (to - from) / step and of
// from * factor^k: a range from 0.1 to 0.5 by 0.1 ends at 0.5.
constexpr double kSlack = 1e-12;

[[noreturn]] void fail_at(const toml::node& node, const std::string& file, const std::string& what) {
  throw ConfigError(fmt::format("{}: {}", scenario::location(node.source(), file), what));
}

// A count as a person reads it: 34657360, or 1.84e+19 for the absurd ones.
std::string count_text(double n) { return n < 1e15 ? fmt::format("{:.0f}", n) : fmt::format("{:.3g}", n); }

// Steps from `from` while within `to`: (to - from) / step of them, or log(to / from) / log(factor).
double length_of(const Range& range) {
  const double a = range.from, b = range.to, s = range.by;
  const double steps = range.log ? std::log(b / a) / std::log(s) : (b - a) / s;
  return std::floor(steps * (1.0 + kSlack)) + 1.0;
}

}  // namespace

std::string float_text(double v) {
  std::string s = fmt::format("{:.12g}", v);
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  return s;
}

Range read_range(const std::string& key, const toml::table& table, const std::string& file, const std::string& where) {
  scenario::TomlReader r(table, where + ".range", file);
  const toml::node* from = r.raw("from");
  const toml::node* to = r.raw("to");
  const toml::node* step = r.raw("step");
  const toml::node* factor = r.raw("factor");
  r.finish();
  if (from == nullptr || to == nullptr) r.fail_table("a range needs from and to, and step or factor");
  if ((step == nullptr) == (factor == nullptr)) r.fail_table("a range has a step or a factor (a log range), one of them");
  Range range;
  range.key = key;
  range.log = factor != nullptr;
  range.by_node = range.log ? factor : step;
  range.file = file;
  range.where = where;
  const std::pair<const char*, const toml::node*> parts[] = {{"from", from}, {"to", to}, {range.log ? "factor" : "step", range.by_node}};
  for (const auto& [name, node] : parts) {
    if (!node->is_number()) fail_at(*node, file, fmt::format("{}: from, to, step and factor are numbers", where));
    const double v = *node->value<double>();
    if (std::isnan(v)) fail_at(*node, file, fmt::format("{}: {} = nan is not a number", where, name));
    if (std::isinf(v)) fail_at(*node, file, fmt::format("{}: {} = {} is not a finite number", where, name, v > 0 ? "inf" : "-inf"));
  }
  range.integers = from->is_integer() && to->is_integer() && range.by_node->is_integer();
  range.from = *from->value<double>();
  range.to = *to->value<double>();
  range.by = *range.by_node->value<double>();
  const toml::node& by = *range.by_node;
  const double a = range.from, b = range.to, s = range.by;
  if (!range.log) {
    if (s == 0.0) fail_at(by, file, fmt::format("{}: the step cannot be 0", where));
    if ((b - a) / s < 0.0) fail_at(by, file, fmt::format("{}: from {} the step {} never reaches {}", where, a, s, b));
    return range;
  }
  if (s <= 0.0) fail_at(by, file, fmt::format("{}: factor = {} must be above 0", where, s));
  if (s == 1.0) fail_at(by, file, fmt::format("{}: factor = 1 never leaves {}: a log range needs a factor above 1 (or below 1 to go down)", where, a));
  const bool up = s > 1.0 && a > 0.0 && b >= a;
  const bool down = s < 1.0 && b > 0.0 && a >= b;
  if (!up && !down) fail_at(by, file, fmt::format("{}: a factor range needs 0 < from <= to with factor > 1, or from >= to > 0 with 0 < factor < 1", where));
  return range;
}

double range_length(const Range& range, double max_values) {
  const double a = range.from, b = range.to, s = range.by;
  const double n = length_of(range);
  if (n > max_values || !std::isfinite(n)) {
    const std::string how = range.log ? fmt::format("by factor {}", s) : fmt::format("by step {}", s);
    fail_at(*range.by_node, range.file,
            fmt::format("{}: from {} to {} {} makes {} values, more than an axis may have ({})", range.where, a, b, how,
                        std::isfinite(n) ? count_text(n) : "endless", count_text(max_values)));
  }
  return n;
}

std::vector<Override> range_values(const Range& range) {
  const double a = range.from, b = range.to, s = range.by;
  const auto text = [&](double v) { return range.integers ? fmt::format("{}", static_cast<std::int64_t>(std::llround(v))) : float_text(v); };
  const double n = length_of(range);
  std::vector<Override> out;
  out.reserve(static_cast<std::size_t>(n));
  if (!range.log) {
    for (double k = 0; k < n; ++k) out.push_back({range.key, text(a + k * s), text(a + k * s)});
    return out;
  }
  const bool up = s > 1.0;
  double v = a;
  // n bounds the loop, whatever the rounding of a * s^k near `to`.
  for (double k = 0; k <= n && (up ? v <= b * (1.0 + kSlack) : v >= b * (1.0 - kSlack)); ++k, v = a * std::pow(s, k)) {
    const std::string t = text(v);
    if (!out.empty() && out.back().toml == t) continue;  // two steps that print alike (12 digits) are one value
    out.push_back({range.key, t, t});
  }
  return out;
}

}  // namespace pagecache::sweep
