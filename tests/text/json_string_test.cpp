// JSON string literals (src/text/json_string.hpp), read back by an independent parser
// (nlohmann::json, which rejects invalid UTF-8 and raw control characters).
#include "text/json_string.hpp"

#include "text/utf8.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <random>
#include <string>

using pagecache::text::json_string;
using pagecache::text::valid_utf8;

namespace {

std::string read_back(const std::string& literal) {
  nlohmann::json j;
  INFO(literal);
  REQUIRE_NOTHROW(j = nlohmann::json::parse(literal));
  REQUIRE(j.is_string());
  return j.get<std::string>();
}

}  // namespace

TEST_CASE("every ASCII character reads back from its JSON string as itself", "[text][json]") {
  for (int c = 0; c < 0x80; ++c) {
    const std::string s(1, static_cast<char>(c));
    CHECK(read_back(json_string(s)) == s);
  }
  CHECK(json_string("a\"b\\c\n\t\r\b\f\x01\x1F\x7F/") == R"("a\"b\\c\n\t\r\b\f\u0001\u001f)" "\x7F" R"(/")");
}

TEST_CASE("random bytes give valid JSON that reads back as the text with U+FFFD for each ill-formed part", "[text][json]") {
  // Bytes drawn so that well-formed, truncated, overlong and surrogate sequences all occur;
  // what valid_utf8 gives is checked against nlohmann's own replacement (its serialiser
  // replaces ill-formed UTF-8 with U+FFFD the same way, by maximal subpart).
  const unsigned char pool[] = {0x00, 0x01, 0x0A, 0x1F, '"', '\\', 'a', 0x7F, 0x80, 0x8F, 0x90, 0x9F, 0xA0, 0xBF,
                                0xC0, 0xC1, 0xC2, 0xDF, 0xE0, 0xE2, 0xED, 0xEF, 0xF0, 0xF4, 0xF5, 0xFF};
  std::mt19937 random(15);
  for (int n = 0; n < 20000; ++n) {
    std::string s;
    const int length = std::uniform_int_distribution<int>(0, 10)(random);
    for (int i = 0; i < length; ++i) s += static_cast<char>(pool[std::uniform_int_distribution<std::size_t>(0, sizeof pool - 1)(random)]);
    const std::string repaired = nlohmann::json(s).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    INFO(nlohmann::json(s).dump(-1, ' ', true, nlohmann::json::error_handler_t::replace));
    REQUIRE(read_back(json_string(s)) == read_back(repaired));
    REQUIRE(read_back(json_string(s)) == valid_utf8(s));
  }
}
