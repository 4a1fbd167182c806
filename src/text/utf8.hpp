#pragma once
// UTF-8 as the outputs need it: which bytes form a well-formed character (Unicode §3.9,
// Table 3-7: no overlong forms, no surrogates, nothing above U+10FFFF, no truncated
// sequence), and a string made valid by replacing each ill-formed part with U+FFFD.

#include <cstddef>
#include <string>
#include <string_view>

namespace pagecache::text {

/// U+FFFD REPLACEMENT CHARACTER, in UTF-8.
inline constexpr std::string_view kReplacement = "\xEF\xBF\xBD";

/// The first character of a non-empty `s`: its length in bytes and its code point, or, if it is
/// ill-formed, the length of the "maximal subpart" that one U+FFFD replaces (Unicode's
/// recommended practice, also WHATWG's and Python's: "\xE2\x82" truncated is one U+FFFD,
/// "\xC0\xAF" two, "\xED\xA0\x80" three).
struct Utf8Char {
  std::size_t length = 1;
  char32_t code_point = 0;  ///< U+FFFD when ill-formed
  bool valid = false;
};
Utf8Char next_utf8_char(std::string_view s);

/// `s` with each ill-formed part replaced by U+FFFD: always valid UTF-8, `s` itself if it was.
std::string valid_utf8(std::string_view s);

}  // namespace pagecache::text
