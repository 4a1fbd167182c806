// UTF-8 validation and repair (src/text/utf8.hpp): every Unicode scalar value is accepted
// as itself, everything else ill-formed is replaced part by part as Unicode recommends.
#include "text/utf8.hpp"

#include <catch2/catch.hpp>

#include <cstdint>
#include <string>

using pagecache::text::next_utf8_char;
using pagecache::text::valid_utf8;

namespace {

const std::string R = "\xEF\xBF\xBD";  // U+FFFD

// The textbook encoder, independent of the decoder under test.
std::string encode(char32_t c) {
  std::string out;
  if (c < 0x80) {
    out += static_cast<char>(c);
  } else if (c < 0x800) {
    out += {static_cast<char>(0xC0 | (c >> 6)), static_cast<char>(0x80 | (c & 0x3F))};
  } else if (c < 0x10000) {
    out += {static_cast<char>(0xE0 | (c >> 12)), static_cast<char>(0x80 | ((c >> 6) & 0x3F)), static_cast<char>(0x80 | (c & 0x3F))};
  } else {
    out += {static_cast<char>(0xF0 | (c >> 18)), static_cast<char>(0x80 | ((c >> 12) & 0x3F)),
            static_cast<char>(0x80 | ((c >> 6) & 0x3F)), static_cast<char>(0x80 | (c & 0x3F))};
  }
  return out;
}

}  // namespace

TEST_CASE("every Unicode scalar value decodes to itself, and every surrogate is ill-formed", "[text][utf8]") {
  // 1.1 million cases: Catch is told only of a failure.
  for (char32_t c = 0; c <= 0x10FFFF; ++c) {
    const std::string bytes = encode(c);
    const auto u = next_utf8_char(bytes);
    // ED A0..BF is never a valid start: ED alone is replaced, then each continuation byte.
    const bool ok = c >= 0xD800 && c <= 0xDFFF ? !u.valid && valid_utf8(bytes) == R + R + R
                                               : u.valid && u.length == bytes.size() && u.code_point == c && valid_utf8(bytes) == bytes;
    if (!ok) FAIL("U+" << std::hex << static_cast<std::uint32_t>(c));
  }
  SUCCEED("all 0x110000 code points");
}

TEST_CASE("ill-formed UTF-8 is replaced by one U+FFFD per maximal subpart", "[text][utf8]") {
  // The Unicode Standard's own example (chapter 3, U+FFFD substitution of maximal subparts).
  CHECK(valid_utf8("\x61\xF1\x80\x80\xE1\x80\xC2\x62\x80\x63\x80\xBF\x64") == "a" + R + R + R + "b" + R + "c" + R + R + "d");
  // Overlong forms: C0/C1 are never leads; E0 80 and F0 80 break at their second byte.
  CHECK(valid_utf8("\xC0\xAF") == R + R);
  CHECK(valid_utf8("\xC1\xBF") == R + R);
  CHECK(valid_utf8("\xE0\x80\xAF") == R + R + R);
  CHECK(valid_utf8("\xF0\x80\x80\xAF") == R + R + R + R);
  // Above U+10FFFF: F4 90.. and the leads F5-FF.
  CHECK(valid_utf8("\xF4\x90\x80\x80") == R + R + R + R);
  CHECK(valid_utf8("\xF5\x80\x80\x80") == R + R + R + R);
  CHECK(valid_utf8("\xFF") == R);
  CHECK(valid_utf8("\xFE\xFF") == R + R);
  // Truncated sequences: one U+FFFD for what was there, at the end or before another character.
  CHECK(valid_utf8("\xE2\x82") == R);
  CHECK(valid_utf8("x\xE2\x82y") == "x" + R + "y");
  CHECK(valid_utf8("\xF0\x9F\x9A") == R);
  CHECK(valid_utf8("\xF0\x9F\x9A\xE2\x82\xAC") == R + "\xE2\x82\xAC");
  CHECK(valid_utf8("\xC3") == R);
  // A lone continuation byte.
  CHECK(valid_utf8("\x80") == R);
  // The lengths of the parts replaced.
  CHECK(next_utf8_char("\xF0\x9F\x9A").length == 3);
  CHECK(next_utf8_char("\xE2\x82(").length == 2);
  CHECK(next_utf8_char("\xED\xA0\x80").length == 1);
  CHECK(next_utf8_char("\xFF\x80").length == 1);
}

TEST_CASE("well-formed text passes through valid_utf8 unchanged", "[text][utf8]") {
  const std::string text = "plain ASCII, \x01\x7F controls, n\xC3\xA4me, \xE2\x82\xAC, \xF0\x9F\x9A\x80, \xEF\xBF\xBD, \xF4\x8F\xBF\xBF";
  CHECK(valid_utf8(text) == text);
  CHECK(valid_utf8("").empty());
}
