#include "text/utf8.hpp"

namespace pagecache::text {

Utf8Char next_utf8_char(std::string_view s) {
  const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(s[i]); };
  const unsigned char lead = byte(0);
  if (lead < 0x80) return {1, lead, true};
  // Table 3-7: the lead byte fixes the number of continuation bytes and the range of the
  // first one (which is what excludes overlong forms, surrogates and code points > U+10FFFF).
  std::size_t continuation = 0;
  unsigned char low = 0x80, high = 0xBF;
  char32_t cp = 0;
  if (lead >= 0xC2 && lead <= 0xDF) {
    continuation = 1, cp = lead & 0x1F;
  } else if (lead >= 0xE0 && lead <= 0xEF) {
    continuation = 2, cp = lead & 0x0F;
    if (lead == 0xE0) low = 0xA0;
    if (lead == 0xED) high = 0x9F;
  } else if (lead >= 0xF0 && lead <= 0xF4) {
    continuation = 3, cp = lead & 0x07;
    if (lead == 0xF0) low = 0x90;
    if (lead == 0xF4) high = 0x8F;
  } else {
    return {1, 0xFFFD, false};  // 80-C1 (continuation, overlong lead) or F5-FF
  }
  for (std::size_t i = 1; i <= continuation; ++i) {
    if (i >= s.size() || byte(i) < low || byte(i) > high) return {i, 0xFFFD, false};
    cp = (cp << 6) | (byte(i) & 0x3F);
    low = 0x80, high = 0xBF;
  }
  return {continuation + 1, cp, true};
}

std::string valid_utf8(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  while (!s.empty()) {
    const Utf8Char c = next_utf8_char(s);
    if (c.valid) out.append(s.substr(0, c.length));
    else out.append(kReplacement);
    s.remove_prefix(c.length);
  }
  return out;
}

}  // namespace pagecache::text
