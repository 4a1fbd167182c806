// The outputs stay readable whatever the names hold: summary.json is valid UTF-8 JSON to an
// independent parser.
#include "report/outputs.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <string>

using pagecache::report::summary_json;

TEST_CASE("summary.json is valid UTF-8 JSON when the source path holds invalid UTF-8 and control characters", "[report][json]") {
  const std::string fffd = "\xEF\xBF\xBD";
  pagecache::Scenario s;
  // A lone 0xFF, an overlong '/', a surrogate (U+D800), a truncated euro sign, then controls,
  // DEL, quotes, a backslash and well-formed non-ASCII (e, euro, G clef).
  s.source = "dir\xFF/x\xC0\xAF/y\xED\xA0\x80/z\xE2\x82/\x01\x1F\n\t\r\b\f\x7F\"q\"\\ \xC3\xA9\xE2\x82\xAC\xF0\x9D\x84\x9E\xE2\x82";
  const std::string expected = "dir" + fffd + "/x" + fffd + fffd + "/y" + fffd + fffd + fffd + "/z" + fffd +
                               "/\x01\x1F\n\t\r\b\f\x7F\"q\"\\ \xC3\xA9\xE2\x82\xAC\xF0\x9D\x84\x9E" + fffd;
  pagecache::RunResult r;
  r.summary.makespan = 12.5;
  r.cache_not_recorded = "too many rows\n\x02";
  const std::string text = summary_json(s, r);
  nlohmann::json j;
  REQUIRE_NOTHROW(j = nlohmann::json::parse(text));
  CHECK(j.at("scenario").get<std::string>() == expected);
  CHECK(j.at("cache_contents").get<std::string>() == "not recorded: too many rows\n\x02");
  CHECK(j.at("makespan_s").get<double>() == 12.5);
  CHECK_THAT(text, Catch::Contains("\"makespan_s\": 12.500000,"));
  // Control characters are escaped, not written raw (JSON forbids them in strings).
  CHECK_THAT(text, Catch::Contains(R"(/\u0001\u001f\n\t\r\b\f)"));
}
