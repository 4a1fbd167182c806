#include "formats/fio/values.hpp"

#include <fmt/format.h>

#include <array>
#include <cctype>
#include <cmath>
#include <limits>

namespace pagecache::formats::fio {

namespace {

constexpr std::int64_t kMax = std::numeric_limits<std::int64_t>::max();

std::string lower(std::string_view text) {
  std::string out(text);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}


}  // namespace

std::string label(const RawOption& option) {
  if (!option_shaped(option.key)) return "an option line";
  if (option.included) return fmt::format("option '{}'", option.key);
  return fmt::format("option '{}={}'", option.key, option.value);
}

std::string shown_value(const RawOption& option, std::string_view text) {
  return option.included ? std::string("its value") : fmt::format("'{}'", text);
}

namespace {

struct Number {
  std::int64_t value = 0;
  std::string suffix;  // what follows the digits, lower-cased
};

// Leading digits (decimal, or hex after 0x), refusing fractions and values past int64.
Number read_digits(const RawOption& option, std::string_view text, bool allow_negative) {
  std::size_t i = 0;
  const bool negative = !text.empty() && text[0] == '-';
  if (negative && !allow_negative) fail(option, fmt::format("{}: a negative value is not allowed", label(option)));
  if (negative) ++i;
  const bool hex = text.size() > i + 1 && text[i] == '0' && (text[i + 1] == 'x' || text[i + 1] == 'X');
  if (hex) i += 2;
  const int base = hex ? 16 : 10;
  const std::size_t first = i;
  std::int64_t value = 0;
  for (; i < text.size(); ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    const int digit = std::isdigit(c) != 0 ? c - '0' : (hex && std::isxdigit(c) != 0 ? std::tolower(c) - 'a' + 10 : -1);
    if (digit < 0) break;
    if (value > (kMax - digit) / base) fail(option, fmt::format("{}: the number is too large", label(option)));
    value = value * base + digit;
  }
  if (i == first) fail(option, fmt::format("{}: {} is not a number", label(option), shown_value(option, text)));
  // Deliberate difference: fio reads no fractions and takes 1.5k as 1 byte, 1.5ms as 1 s.
  if (i < text.size() && text[i] == '.') {
    fail(option, fmt::format("{}: fio reads no fractions (it would take {} as {}); write a whole number, in a smaller unit if need be",
                             label(option), shown_value(option, text), option.included ? "its whole part" : std::string(text.substr(0, i))));
  }
  return Number{.value = negative ? -value : value, .suffix = lower(text.substr(i))};
}

// The multiplier of a size suffix under kb_base, or 0 if it is not one.
std::int64_t size_multiplier(const std::string& suffix, int kb_base) {
  if (suffix.empty() || suffix == "b") return 1;
  static constexpr std::string_view kPowers = "kmgtp";
  const std::size_t power = kPowers.find(suffix[0]);
  if (power == std::string_view::npos) return 0;
  const std::string_view rest = std::string_view(suffix).substr(1);
  std::int64_t base = kb_base;
  // fio's rule: the three-letter IEC forms use the opposite base; "ki" is not one of them.
  if (rest == "ib") {
    base = kb_base == 1024 ? 1000 : 1024;
  } else if (!rest.empty() && rest != "b" && rest != "i") {
    return 0;
  }
  std::int64_t multiplier = 1;
  for (std::size_t p = 0; p <= power; ++p) multiplier *= base;
  return multiplier;
}

}  // namespace

std::int64_t parse_size(const RawOption& option, std::string_view text, int kb_base, bool allow_negative) {
  const Number number = read_digits(option, text, allow_negative);
  const std::int64_t multiplier = size_multiplier(number.suffix, kb_base);
  // Deliberate difference: fio takes an unknown suffix as bytes (4x is 4).
  if (multiplier == 0) {
    fail(option, fmt::format("{}: unknown size suffix {} (fio accepts b, k, kb, kib, m, mb, mib, g, t, p in any case; "
                             "kib, mib ... are 1000-based under kb_base=1024)",
                             label(option), shown_value(option, number.suffix)));
  }
  if (std::abs(number.value) > kMax / multiplier) fail(option, fmt::format("{}: the size is too large", label(option)));
  return number.value * multiplier;
}

SizeOrPercent parse_size_or_percent(const RawOption& option, std::string_view text, int kb_base) {
  if (!text.empty() && text.back() == '%') {
    const Number number = read_digits(option, text.substr(0, text.size() - 1), false);
    // Deliberate difference: fio reads 150% as a huge byte count, and 0% as a sentinel.
    if (!number.suffix.empty() || number.value < 1 || number.value > 100) {
      fail(option, fmt::format("{}: a percentage is a whole number from 1 to 100", label(option)));
    }
    return SizeOrPercent{.bytes = 0, .percent = static_cast<int>(number.value)};
  }
  return SizeOrPercent{.bytes = parse_size(option, text, kb_base), .percent = 0};
}

std::int64_t parse_count(const RawOption& option, int kb_base, std::int64_t min, std::int64_t max) {
  require_single_value(option);
  const std::int64_t value = parse_size(option, option.value, kb_base);
  if (value < min || value > max) fail(option, fmt::format("{}: must be from {} to {}", label(option), min, max));
  return value;
}

double parse_time(const RawOption& option, double default_seconds) {
  require_single_value(option);
  const Number number = read_digits(option, option.value, false);
  struct Unit {
    std::string_view suffix;
    double seconds;
  };
  static constexpr std::array<Unit, 8> kUnits{{{"us", 1e-6}, {"usec", 1e-6}, {"ms", 1e-3}, {"msec", 1e-3},
                                                {"s", 1.0}, {"m", 60.0}, {"h", 3600.0}, {"d", 86400.0}}};
  double unit = number.suffix.empty() ? default_seconds : 0.0;
  for (const Unit& u : kUnits) {
    if (number.suffix == u.suffix) unit = u.seconds;
  }
  // Deliberate difference: fio takes an unknown suffix as microseconds (runtime=10sec is 10 us).
  if (unit == 0.0) {
    fail(option, fmt::format("{}: unknown time suffix {} (fio accepts us, usec, ms, msec, s, m, h, d; "
                             "it would read {} as {} microseconds)",
                             label(option), shown_value(option, number.suffix), shown_value(option, option.value), number.value));
  }
  // Whole microseconds, as fio keeps times; the bound keeps the product exact enough and finite.
  if (static_cast<double>(number.value) * unit > 1e12) fail(option, fmt::format("{}: the time is too long", label(option)));
  return static_cast<double>(number.value) * unit;
}

bool parse_bool(const RawOption& option) {
  if (option.bare) fail(option, fmt::format("option '{}' needs a value: write '{}=1' or '{}=0'", option.key, option.key, option.key));
  if (option.value != "0" && option.value != "1") fail(option, fmt::format("{}: the value must be 0 or 1", label(option)));
  return option.value == "1";
}

bool parse_flag(const RawOption& option) {
  if (option.bare) return true;
  if (option.value.empty() || option.value.find_first_not_of("0123456789") != std::string::npos) {
    fail(option, fmt::format("{}: the value must be a whole number (or write '{}' alone for 1)", label(option), option.key));
  }
  return option.value.find_first_not_of('0') != std::string::npos;
}

std::vector<std::string> split_directions(std::string_view value) {
  std::vector<std::string> pieces;
  char separator = ',';
  if (value.find(',') == std::string_view::npos) separator = value.find(':') != std::string_view::npos ? ':' : '-';
  for (std::size_t begin = 0;;) {
    const std::size_t end = value.find(separator, begin);
    pieces.emplace_back(value.substr(begin, end == std::string_view::npos ? std::string_view::npos : end - begin));
    if (end == std::string_view::npos) break;
    begin = end + 1;
  }
  return pieces;
}

std::vector<std::string> split_names(std::string_view value) {
  while (!value.empty() && std::isspace(static_cast<unsigned char>(value.front())) != 0) value.remove_prefix(1);
  while (!value.empty() && std::isspace(static_cast<unsigned char>(value.back())) != 0) value.remove_suffix(1);
  std::vector<std::string> names;
  std::string current;
  for (std::size_t i = 0; i < value.size(); ++i) {
    if (value[i] == '\\' && i + 1 < value.size() && value[i + 1] == ':') {
      current += ':';
      ++i;
    } else if (value[i] == ':') {
      if (!current.empty()) names.push_back(std::move(current));
      current.clear();
    } else {
      current += value[i];
    }
  }
  if (!current.empty()) names.push_back(std::move(current));
  return names;
}

void require_single_value(const RawOption& option) {
  if (option.bare || option.value.empty()) fail(option, fmt::format("option '{}' needs a value", option.key));
  if (option.value.find_first_of(",:") != std::string::npos || option.value.find('-', 1) != std::string::npos) {
    fail(option, fmt::format("{}: takes a single value (fio would read only the part before ',', ':' or '-')", label(option)));
  }
}

}  // namespace pagecache::formats::fio
