#include "formats/simgrid/xml/radical.hpp"

#include <pagecache/error.hpp>

#include "formats/simgrid/xml/text.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>

namespace pagecache::formats::simgrid {

namespace {

int number(std::string_view part, std::string_view text) {
  const std::string_view digits = sg_trim(part);
  int value = 0;
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  const bool all_digits = !digits.empty() && digits.find_first_not_of("0123456789") == std::string_view::npos;
  if (!all_digits || error != std::errc() || end != digits.data() + digits.size()) {
    throw ConfigError(fmt::format("'{}': '{}' is not a number of 0 to {}", sg_shown(text), sg_shown(digits), std::numeric_limits<int>::max()));
  }
  return value;
}

}  // namespace

std::vector<int> parse_sg_radical(std::string_view text, std::size_t max_count) {
  std::vector<std::pair<int, int>> ranges;
  std::int64_t count = 0;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    const std::string_view group = text.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start);
    const std::size_t dash = group.find('-');
    const int first = number(group.substr(0, dash), text);
    const int last = dash == std::string_view::npos ? first : number(group.substr(dash + 1), text);
    if (last < first) throw ConfigError(fmt::format("'{}': the range '{}' runs backwards", sg_shown(text), sg_shown(sg_trim(group))));
    count += std::int64_t{last} - first + 1;
    if (count > static_cast<std::int64_t>(max_count)) {
      throw ConfigError(fmt::format("'{}' names more than {} hosts, the most a cluster may have here", sg_shown(text), max_count));
    }
    ranges.emplace_back(first, last);
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  std::vector<int> numbers;
  numbers.reserve(static_cast<std::size_t>(count));
  for (const auto& [first, last] : ranges) {
    for (std::int64_t n = first; n <= last; ++n) numbers.push_back(static_cast<int>(n));
  }
  return numbers;
}

}  // namespace pagecache::formats::simgrid
