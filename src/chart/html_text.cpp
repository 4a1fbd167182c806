#include "chart/html_text.hpp"

#include "text/utf8.hpp"

#include <fmt/compile.h>
#include <fmt/format.h>

#include <cmath>

namespace pagecache::chart {

std::string escape(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  while (!s.empty()) {
    const text::Utf8Char c = text::next_utf8_char(s);
    const std::string_view bytes = s.substr(0, c.length);
    s.remove_prefix(c.length);
    if (!c.valid) {
      out += text::kReplacement;
      continue;
    }
    switch (c.code_point) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      case '\t':
      case '\n': out += bytes; break;
      default:
        // Control characters are not allowed in HTML text (C0, DEL, C1).
        if (c.code_point < 0x20 || (c.code_point >= 0x7F && c.code_point < 0xA0)) out += text::kReplacement;
        else out += bytes;
    }
  }
  return out;
}

std::string fixed(double value, int decimals) {
  const double scale = std::pow(10.0, decimals);
  if (std::abs(value) * scale < 0.5) value = 0.0;  // no "-0.0"
  return fmt::format(FMT_COMPILE("{:.{}f}"), value, decimals);  // parsed once: a report formats thousands
}

}  // namespace pagecache::chart
