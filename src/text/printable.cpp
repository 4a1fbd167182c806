#include "text/printable.hpp"

#include "text/utf8.hpp"

#include <fmt/format.h>

#include <cstdint>

namespace pagecache::text {

namespace {

bool shown_escaped(char32_t cp) {
  return cp < 0x20 || (cp >= 0x7F && cp <= 0x9F) || cp == 0x2028 || cp == 0x2029 ||  // controls, separators
         cp == 0x200E || cp == 0x200F || (cp >= 0x202A && cp <= 0x202E) || (cp >= 0x2066 && cp <= 0x2069);  // bidi
}

}  // namespace

std::string printable(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  while (!s.empty()) {
    const Utf8Char c = next_utf8_char(s);
    if (!c.valid) out.append(kReplacement);
    else if (c.code_point == '\n') out += "\\n";
    else if (c.code_point == '\r') out += "\\r";
    else if (c.code_point == '\t') out += "\\t";
    else if (shown_escaped(c.code_point)) out += fmt::format("\\u{:04x}", static_cast<std::uint32_t>(c.code_point));
    else out.append(s.substr(0, c.length));
    s.remove_prefix(c.length);
  }
  return out;
}

}  // namespace pagecache::text
