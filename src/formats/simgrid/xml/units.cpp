#include "formats/simgrid/xml/units.hpp"

#include <pagecache/error.hpp>

#include "formats/simgrid/xml/text.hpp"

#include <fmt/format.h>

#include <array>
#include <charconv>
#include <cmath>
#include <string>
#include <unordered_map>

namespace pagecache::formats::simgrid {

namespace {

using UnitTable = std::unordered_map<std::string, double>;

constexpr std::array<std::string_view, 8> kDecimalPrefixes{"k", "M", "G", "T", "P", "E", "Z", "Y"};
constexpr std::array<std::string_view, 8> kBinaryPrefixes{"Ki", "Mi", "Gi", "Ti", "Pi", "Ei", "Zi", "Yi"};
constexpr std::array<std::string_view, 8> kDecimalWords{"kilo", "mega", "giga", "tera", "peta", "exa", "zeta", "yotta"};

// `unit` worth `value`, then each prefix worth `step` times the one before, multiplied in
// turn as SimGrid does, so that every factor is the double SimGrid gets.
void add_family(UnitTable& table, std::string_view unit, double value, double step, const std::array<std::string_view, 8>& prefixes) {
  table.emplace(std::string(unit), value);
  for (std::string_view prefix : prefixes) {
    value *= step;
    table.emplace(std::string(prefix) + std::string(unit), value);
  }
}

UnitTable bytes_and_bits(std::string_view bits, std::string_view bytes) {
  UnitTable table;
  for (const auto& [unit, value] : {std::pair{bits, 0.125}, std::pair{bytes, 1.0}}) {
    add_family(table, unit, value, 1024.0, kBinaryPrefixes);
    add_family(table, unit, value, 1000.0, kDecimalPrefixes);
  }
  return table;
}

const UnitTable& bandwidth_units() {
  static const UnitTable table = bytes_and_bits("bps", "Bps");
  return table;
}

const UnitTable& size_units() {
  static const UnitTable table = bytes_and_bits("b", "B");
  return table;
}

const UnitTable& speed_units() {
  static const UnitTable table = [] {
    UnitTable t;
    add_family(t, "f", 1.0, 1000.0, kDecimalPrefixes);
    add_family(t, "flops", 1.0, 1000.0, kDecimalWords);
    return t;
  }();
  return table;
}

const UnitTable& time_units() {
  static const UnitTable table{{"w", 7 * 24 * 3600.0}, {"d", 24 * 3600.0}, {"h", 3600.0}, {"m", 60.0}, {"s", 1.0},
                               {"ms", 1e-3},         {"us", 1e-6},        {"ns", 1e-9},   {"ps", 1e-12}};
  return table;
}

struct Kind {
  const char* what;
  const UnitTable& (*units)();
  std::string_view base;
  const char* examples;
};

constexpr Kind kBandwidth{"bandwidth", bandwidth_units, "Bps", "Bps, kBps, MBps, GBps, KiBps, MiBps, GiBps, or bps, Mbps, Gbps, Mibps for bits"};
constexpr Kind kTime{"time", time_units, "s", "w, d, h, m, s, ms, us, ns, ps"};
constexpr Kind kSpeed{"speed", speed_units, "f", "f, kf, Mf, Gf, Tf, or flops, megaflops, gigaflops"};
constexpr Kind kSize{"size", size_units, "B", "B, kB, MB, GB, TB, KiB, MiB, GiB, TiB, or b, Mb, Gb for bits"};

struct Number {
  double value = 0;
  std::string_view unit;  // what follows the number
};

// SimGrid reads the number with strtod; from_chars reads the same decimal forms, and the first
// character is checked so that strtod's others (inf, nan, hexadecimal, a sign) are refused.
Number split_number(std::string_view text, const Kind& kind) {
  const std::string_view s = sg_trim(text);
  if (s.empty()) throw ConfigError(fmt::format("empty {}", kind.what));
  if (s.front() == '-') throw ConfigError(fmt::format("'{}' is negative", sg_shown(text)));
  const bool starts_as_number = (s.front() >= '0' && s.front() <= '9') || s.front() == '.';
  Number n;
  const auto [end, error] = starts_as_number ? std::from_chars(s.data(), s.data() + s.size(), n.value)
                                             : std::from_chars_result{s.data(), std::errc::invalid_argument};
  if (error == std::errc::result_out_of_range) throw ConfigError(fmt::format("'{}' is out of range", sg_shown(text)));
  if (error != std::errc()) throw ConfigError(fmt::format("'{}' is not a {}: it should start with a number", sg_shown(text), kind.what));
  n.unit = s.substr(static_cast<std::size_t>(end - s.data()));
  return n;
}

double parse(std::string_view text, const Kind& kind) {
  const Number n = split_number(text, kind);
  const std::string_view unit = n.unit.empty() ? kind.base : n.unit;
  const UnitTable& units = kind.units();
  const auto found = units.find(std::string(unit));
  if (found == units.end()) {
    const bool spaced = unit.front() == ' ' || unit.front() == '\t';
    throw ConfigError(fmt::format("'{}': unknown {} unit '{}' ({}SimGrid's units: {})", sg_shown(text), kind.what, sg_shown(unit),
                                  spaced ? "no space between number and unit; " : "", kind.examples));
  }
  // A fraction of the base unit divides by its inverse, which is exact: 100 * 1e-6 is
  // 9.999999999999999e-05, 100 / 1e6 is 1e-4 (SimGrid multiplies; the two differ by an ulp).
  const double value = found->second < 1.0 ? n.value / std::round(1.0 / found->second) : n.value * found->second;
  if (!std::isfinite(value)) throw ConfigError(fmt::format("'{}' is too large", sg_shown(text)));
  return value;
}

}  // namespace

double parse_sg_bandwidth(std::string_view text) { return parse(text, kBandwidth); }
double parse_sg_time(std::string_view text) { return parse(text, kTime); }
double parse_sg_speed(std::string_view text) { return parse(text, kSpeed); }
double parse_sg_size(std::string_view text) { return parse(text, kSize); }

bool sg_lacks_unit(std::string_view text) {
  const std::string_view s = sg_trim(text);
  double value = 0;
  const auto [end, error] = std::from_chars(s.data(), s.data() + s.size(), value);
  return error == std::errc() && end == s.data() + s.size() && value != 0.0;
}

}  // namespace pagecache::formats::simgrid
