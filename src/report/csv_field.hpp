#pragma once
// One text field of the CSV outputs (app, task, phase, host and file names). Numbers are
// written by the writers themselves and never pass through here.

#include "text/formula.hpp"

#include <fmt/format.h>

#include <array>
#include <string_view>

namespace pagecache::report {

namespace detail {

// Bytes that make a field quoted (RFC 4180: comma, quote, CR, LF).
inline constexpr auto kQuotedByte = [] {
  std::array<bool, 256> t{};
  for (unsigned char c : {',', '"', '\r', '\n'}) t[c] = true;
  return t;
}();

void append_special_csv_field(fmt::memory_buffer& out, std::string_view text);

}  // namespace detail

/// Appends `text` as one CSV field. RFC 4180: a field holding a comma, a double quote, CR or LF,
/// or starting or ending with a space, is enclosed in double quotes, its quotes doubled; any
/// other is written as is. Against formula injection, a field starting with = + - @ TAB or CR
/// is written with a single quote `'` before it (inside the quotes if quoted), which a
/// spreadsheet shows as text: a reader gets the name back by dropping that first `'` (a name
/// that itself starts with `'` is written as is, so a reader cannot tell the two apart).
inline void append_csv_field(fmt::memory_buffer& out, std::string_view text) {
  // The common case, checked in one pass: a plain append.
  bool plain = text.empty() || (!text::starts_formula(text) && text.front() != ' ' && text.back() != ' ');
  for (std::size_t i = 0; plain && i < text.size(); ++i) plain = !detail::kQuotedByte[static_cast<unsigned char>(text[i])];
  if (plain) out.append(text.data(), text.data() + text.size());
  else detail::append_special_csv_field(out, text);
}

}  // namespace pagecache::report
