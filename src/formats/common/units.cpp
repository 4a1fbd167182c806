// Sizes, durations and bandwidths in a scenario's units: reading and writing them (pagecache/units.hpp).
#include <pagecache/error.hpp>
#include <pagecache/units.hpp>

#include <fmt/format.h>

#include <algorithm>
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

constexpr std::array<Unit, 14> kSizeUnits{{{"B", 1.0},
                                            {"kB", 1e3},
                                            {"KB", 1e3},
                                            {"MB", 1e6},
                                            {"GB", 1e9},
                                            {"TB", 1e12},
                                            {"PB", 1e15},
                                            {"EB", 1e18},
                                            {"KiB", 1024.0},
                                            {"MiB", 1024.0 * 1024},
                                            {"GiB", 1024.0 * 1024 * 1024},
                                            {"TiB", 1024.0 * 1024 * 1024 * 1024},
                                            {"PiB", 1024.0 * 1024 * 1024 * 1024 * 1024},
                                            {"EiB", 1024.0 * 1024 * 1024 * 1024 * 1024 * 1024}}};

// Network bandwidths are quoted in bits per second.
constexpr std::array<Unit, 5> kBitUnits{{{"bit", 1.0 / 8}, {"kbit", 1e3 / 8}, {"Mbit", 1e6 / 8}, {"Gbit", 1e9 / 8}, {"Tbit", 1e12 / 8}}};

constexpr std::array<Unit, 7> kTimeUnits{{{"ns", 1e-9}, {"us", 1e-6}, {"ms", 1e-3}, {"s", 1.0}, {"sec", 1.0}, {"min", 60.0}, {"h", 3600.0}}};

using Misspellings = std::array<std::pair<std::string_view, std::string_view>, 8>;
// Spellings people type for a unit we know under another: suggested, never accepted.
constexpr Misspellings kBandwidthMisspellings{
    {{"bps", "bit/s"}, {"kbps", "kbit/s"}, {"Kbps", "kbit/s"}, {"Mbps", "Mbit/s"}, {"Gbps", "Gbit/s"}, {"Tbps", "Tbit/s"}, {"MBps", "MB/s"}, {"GBps", "GB/s"}}};
constexpr Misspellings kTimeMisspellings{
    {{"m", "min"}, {"secs", "s"}, {"second", "s"}, {"seconds", "s"}, {"minute", "min"}, {"minutes", "min"}, {"hour", "h"}, {"hours", "h"}}};

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

bool same_ignoring_case(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
         });
}

template <std::size_t N>
const Unit* find_unit(std::string_view name, const std::array<Unit, N>& table) {
  for (const Unit& u : table) {
    if (u.name == name) return &u;
  }
  return nullptr;
}

// The unit someone typing `unit` meant, if it is a common spelling of one ("Gbps"); else "".
std::string misspelt(std::string_view unit, const Misspellings& misspellings) {
  for (const auto& [typed, meant] : misspellings) {
    if (unit == typed) return std::string(meant);
  }
  return {};
}

// The unit someone typing `unit` meant, if it is one of `table` in other letter case ("gib");
// else "". `suffix` follows it.
template <std::size_t N>
std::string meant_unit(std::string_view unit, const std::array<Unit, N>& table, std::string_view suffix = {}) {
  for (const Unit& u : table) {
    if (same_ignoring_case(unit, u.name)) return std::string(u.name) + std::string(suffix);
  }
  return {};
}

[[noreturn]] void unknown_unit(std::string_view text, const char* what, std::string_view unit, const std::string& meant, const char* examples) {
  if (!meant.empty()) throw ConfigError(fmt::format("'{}': unknown {} unit '{}' (did you mean '{}'?)", text, what, unit, meant));
  throw ConfigError(fmt::format("'{}': unknown {} unit '{}' (use {})", text, what, unit, examples));
}

// value * factor, which must be finite ("1e308 h" is not).
double scaled(double value, double factor, std::string_view text, const char* what) {
  const double result = value * factor;
  if (!std::isfinite(result)) throw ConfigError(fmt::format("'{}': {} too large", text, what));
  return result;
}

}  // namespace

std::int64_t parse_size(std::string_view text) {
  const auto [value, unit] = split_number(text, "size");
  double factor = 1.0;
  if (!unit.empty()) {
    const Unit* u = find_unit(unit, kSizeUnits);
    if (u == nullptr) unknown_unit(text, "size", unit, meant_unit(unit, kSizeUnits), "B, kB, MB, GB, TB, PB, EB, KiB, MiB, GiB, TiB, PiB, EiB");
    factor = u->factor;
  }
  const double bytes = std::round(value * factor);
  if (!(bytes <= static_cast<double>(kMaxBytes))) throw ConfigError(fmt::format("'{}': size too large (at most 1 EiB)", text));
  return static_cast<std::int64_t>(bytes);
}

double parse_bandwidth(std::string_view text) {
  const auto [value, unit] = split_number(text, "bandwidth");
  if (unit.empty()) return value;
  const bool per_second = unit.size() > 2 && unit.substr(unit.size() - 2) == "/s";
  if (per_second) {
    const std::string_view per = unit.substr(0, unit.size() - 2);
    if (const Unit* u = find_unit(per, kSizeUnits)) return scaled(value, u->factor, text, "bandwidth");
    if (const Unit* u = find_unit(per, kBitUnits)) return scaled(value, u->factor, text, "bandwidth");
  }
  std::string_view base = unit;
  if (unit.size() > 2 && same_ignoring_case(unit.substr(unit.size() - 2), "/s")) base = unit.substr(0, unit.size() - 2);
  std::string meant = misspelt(unit, kBandwidthMisspellings);
  if (meant.empty()) meant = meant_unit(base, kSizeUnits, "/s");
  // A lower-case b is a bit ("Mb/s"): the size and the bit unit are both offered.
  const std::string bits = !base.empty() && base.back() == 'b' ? meant_unit(std::string(base.substr(0, base.size() - 1)) + "bit", kBitUnits, "/s")
                                                               : meant_unit(base, kBitUnits, "/s");
  if (meant.empty()) meant = bits;
  else if (!bits.empty() && bits != meant) meant += "' or '" + bits;
  if (!per_second && !meant.empty() && meant.substr(0, base.size()) == base) {
    throw ConfigError(fmt::format("'{}': a bandwidth is a size per second (did you mean '{}'?)", text, meant));
  }
  unknown_unit(text, "bandwidth", unit, meant, "B/s, MB/s, GB/s, MiB/s, GiB/s, Mbit/s, Gbit/s");
}

double parse_duration(std::string_view text) {
  const auto [value, unit] = split_number(text, "duration");
  if (unit.empty()) return value;
  const Unit* u = find_unit(unit, kTimeUnits);
  if (u == nullptr) {
    const std::string meant = misspelt(unit, kTimeMisspellings);
    unknown_unit(text, "duration", unit, meant.empty() ? meant_unit(unit, kTimeUnits) : meant, "ns, us, ms, s, min, h");
  }
  return scaled(value, u->factor, text, "duration");
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

std::string format_instant(double seconds) {
  return std::abs(seconds) <= kMaxSeconds ? fmt::format("{:.6f}", seconds) : fmt::format("{:.6g}", seconds);
}

}  // namespace pagecache::units
