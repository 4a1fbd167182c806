#include "text/json_string.hpp"

#include "text/utf8.hpp"

#include <fmt/format.h>

namespace pagecache::text {

std::string json_string(std::string_view s) {
  std::string out = "\"";
  out.reserve(s.size() + 2);
  while (!s.empty()) {
    const unsigned char c = static_cast<unsigned char>(s.front());
    if (c >= 0x80) {
      const Utf8Char u = next_utf8_char(s);
      out.append(u.valid ? s.substr(0, u.length) : kReplacement);
      s.remove_prefix(u.length);
      continue;
    }
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      case '\r': out += "\\r"; break;
      case '\b': out += "\\b"; break;
      case '\f': out += "\\f"; break;
      default:
        if (c < 0x20) out += fmt::format("\\u{:04x}", c);
        else out += static_cast<char>(c);
    }
    s.remove_prefix(1);
  }
  return out + "\"";
}

}  // namespace pagecache::text
