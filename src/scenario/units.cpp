#include <pagecache/error.hpp>
#include <pagecache/units.hpp>

#include <fmt/format.h>

#include <array>
#include <cctype>
#include <cmath>
#include <utility>

namespace pagecache::units {

namespace {

struct Unit {
  std::string_view name;
  double factor;
};

constexpr std::array<Unit, 10> kSizeUnits{{{"B", 1.0},
                                            {"kB", 1e3},
                                            {"KB", 1e3},
                                            {"MB", 1e6},
                                            {"GB", 1e9},
                                            {"TB", 1e12},
                                            {"KiB", 1024.0},
                                            {"MiB", 1024.0 * 1024},
                                            {"GiB", 1024.0 * 1024 * 1024},
                                            {"TiB", 1024.0 * 1024 * 1024 * 1024}}};

constexpr std::array<Unit, 7> kTimeUnits{{{"ns", 1e-9}, {"us", 1e-6}, {"ms", 1e-3}, {"s", 1.0}, {"sec", 1.0}, {"min", 60.0}, {"h", 3600.0}}};

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

// Splits "12.5 GB" into 12.5 and "GB".
std::pair<double, std::string_view> split_number(std::string_view text, const char* what) {
  const std::string_view s = trim(text);
  std::size_t end = 0;
  while (end < s.size() && (std::isdigit(static_cast<unsigned char>(s[end])) || s[end] == '.' || s[end] == '-' ||
                            s[end] == '+' || s[end] == 'e' || s[end] == 'E')) {
    // Stop at an 'e'/'E' that starts a unit rather than an exponent.
    if ((s[end] == 'e' || s[end] == 'E') && (end + 1 >= s.size() || !(std::isdigit(static_cast<unsigned char>(s[end + 1])) ||
                                                                    s[end + 1] == '-' || s[end + 1] == '+'))) {
      break;
    }
    ++end;
  }
  const std::string number(s.substr(0, end));
  if (number.empty()) throw ConfigError(fmt::format("'{}' is not a {}: it should start with a number", text, what));
  std::size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(number, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != number.size() || !std::isfinite(value)) throw ConfigError(fmt::format("'{}' is not a {}", text, what));
  if (value < 0.0) throw ConfigError(fmt::format("'{}': a {} cannot be negative", text, what));
  return {value, trim(s.substr(end))};
}

template <std::size_t N>
double factor_of(std::string_view unit, const std::array<Unit, N>& table, std::string_view text, const char* what,
                 const char* examples) {
  for (const Unit& u : table) {
    if (u.name == unit) return u.factor;
  }
  throw ConfigError(fmt::format("'{}': unknown {} unit '{}' (use {})", text, what, unit, examples));
}

}  // namespace

std::int64_t parse_size(std::string_view text) {
  const auto [value, unit] = split_number(text, "size");
  const double factor = unit.empty() ? 1.0 : factor_of(unit, kSizeUnits, text, "size", "B, kB, MB, GB, TB, KiB, MiB, GiB, TiB");
  const double bytes = std::round(value * factor);
  if (bytes > 9.2e18) throw ConfigError(fmt::format("'{}': size too large", text));
  return static_cast<std::int64_t>(bytes);
}

double parse_bandwidth(std::string_view text) {
  const auto [value, unit] = split_number(text, "bandwidth");
  if (unit.empty()) return value;
  if (unit.size() < 3 || unit.substr(unit.size() - 2) != "/s") {
    throw ConfigError(fmt::format("'{}': a bandwidth is a size per second, e.g. \"465 MB/s\"", text));
  }
  return value * factor_of(unit.substr(0, unit.size() - 2), kSizeUnits, text, "bandwidth", "B/s, MB/s, GB/s, MiB/s, GiB/s");
}

double parse_duration(std::string_view text) {
  const auto [value, unit] = split_number(text, "duration");
  if (unit.empty()) return value;
  return value * factor_of(unit, kTimeUnits, text, "duration", "ns, us, ms, s, min, h");
}

std::string format_size(std::int64_t bytes) {
  struct Named {
    const char* name;
    std::int64_t factor;
  };
  static constexpr Named kUnits[] = {{"TiB", 1LL << 40}, {"TB", 1'000'000'000'000}, {"GiB", 1LL << 30}, {"GB", 1'000'000'000},
                                     {"MiB", 1LL << 20}, {"MB", 1'000'000},         {"KiB", 1LL << 10}, {"kB", 1'000}};
  if (bytes != 0) {
    for (const Named& u : kUnits) {
      if (bytes % u.factor == 0) return fmt::format("{} {}", bytes / u.factor, u.name);
    }
  }
  return fmt::format("{} B", bytes);
}

std::string format_bandwidth(double bytes_per_second) {
  const double rounded = std::round(bytes_per_second);
  if (rounded == bytes_per_second && rounded < 9e18) return format_size(static_cast<std::int64_t>(rounded)) + "/s";
  return fmt::format("{} B/s", bytes_per_second);
}

std::string format_duration(double seconds) { return fmt::format("{} s", seconds); }

}  // namespace pagecache::units
