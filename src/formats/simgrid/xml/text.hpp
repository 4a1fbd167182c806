#pragma once
// Text helpers shared by the SimGrid platform reader's parts: values trimmed as SimGrid trims
// them, and values from the file quoted in messages safely.

#include "text/printable.hpp"

#include <string>
#include <string_view>

namespace pagecache::formats::simgrid {

/// `s` without the spaces, tabs and line ends around it.
inline std::string_view sg_trim(std::string_view s) {
  constexpr std::string_view kSpaces = " \t\r\n";
  const auto first = s.find_first_not_of(kSpaces);
  if (first == std::string_view::npos) return {};
  return s.substr(first, s.find_last_not_of(kSpaces) - first + 1);
}

/// `s` for a message: printable (no control characters from a hostile file) and cut at 60
/// bytes, since a value may be megabytes long.
inline std::string sg_shown(std::string_view s) {
  constexpr std::size_t kLongest = 60;
  return s.size() <= kLongest ? text::printable(s) : text::printable(s.substr(0, kLongest)) + "...";
}

}  // namespace pagecache::formats::simgrid
