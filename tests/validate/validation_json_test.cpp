// pcsim validate --json (Report::json) is valid JSON whatever the profile and case names hold,
// read back by an independent parser.
#include "validate/validation.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

using pagecache::validate::CaseResult;
using pagecache::validate::Report;

TEST_CASE("pcsim validate's JSON escapes quotes, control characters and invalid UTF-8 in its strings", "[validate][json]") {
  Report report;
  report.profile = "li\"nux\"\n\\ \xFF";
  CaseResult c;
  c.name = "exp\t1 \x01";
  c.mean_error_pct = 1.5;
  c.extra = {{"key \"x\"", 2.25}};
  report.cases = {c};
  nlohmann::json j;
  REQUIRE_NOTHROW(j = nlohmann::json::parse(report.json()));
  REQUIRE(j.size() == 1);
  CHECK(j[0].at("case") == "exp\t1 \x01");
  CHECK(j[0].at("profile") == "li\"nux\"\n\\ \xEF\xBF\xBD");
  CHECK(j[0].at("mean_error_pct") == 1.5);
  CHECK(j[0].at("key \"x\"") == 2.25);
}
