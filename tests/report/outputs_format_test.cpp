// The outputs stay readable whatever the names hold: the CSV files read back field for field
// with an independent RFC 4180 parser and no field starts a spreadsheet formula, summary.json
// is valid UTF-8 JSON to an independent parser, and the terminal summary carries no control
// character. The RunResult is built by hand, as an embedding program could.
#include "report/outputs.hpp"

#include <catch2/catch.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;
using pagecache::readable_summary;
using pagecache::summary_json;
using pagecache::write_cache_csv;
using pagecache::write_memory_csv;
using pagecache::write_timeline_csv;

namespace {

using Rows = std::vector<std::vector<std::string>>;

// RFC 4180's grammar as it reads, with LF as the record end (what pcsim writes): a field is
// either "escaped" (in double quotes, "" for a quote, anything else inside) or not (no comma,
// quote, CR or LF). Anything else fails the test.
Rows parse_csv(const std::string& text) {
  Rows rows;
  std::vector<std::string> row;
  std::size_t i = 0;
  while (i < text.size()) {
    std::string field;
    if (text[i] == '"') {
      for (++i;; ++i) {
        REQUIRE(i < text.size());  // the closing quote is missing
        if (text[i] != '"') {
          field += text[i];
        } else if (i + 1 < text.size() && text[i + 1] == '"') {
          field += '"';
          ++i;
        } else {
          ++i;
          break;
        }
      }
    } else {
      for (; i < text.size() && text[i] != ',' && text[i] != '\n'; ++i) {
        INFO("unquoted field " << field);
        REQUIRE(text[i] != '"');
        REQUIRE(text[i] != '\r');
        field += text[i];
      }
    }
    row.push_back(field);
    REQUIRE(i < text.size());  // every record ends with a line end
    REQUIRE((text[i] == ',' || text[i] == '\n'));
    if (text[i++] == '\n') rows.push_back(std::exchange(row, {}));
  }
  return rows;
}

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / fmt::format("pcsim-format-test-{}-{}", ::getpid(), name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// Names an embedding program could give (the scenario loader may refuse some of them).
const std::vector<std::string> kHostile = {
    "a,\"b\"\n=cmd|' /C calc'!A0",
    "@SUM(1)",
    "-2+3",
    "+1",
    "=1+1",
    "\tindented",
    "\rcarriage return first",
    "tab\tinside",
    " padded ",
    "trailing space ",
    "\"quoted\"",
    "line\r\nbreak",
    "comma,inside",
    "unicode: n\xC3\xA4me \xE5\x90\x8D \xF0\x9F\x9A\x80",
    "'starts with a quote",
    "",
    "plain_name",
};

// What a reader gets back for a name: the name, after the documented ' for a formula start.
std::string as_written(const std::string& name) {
  const bool formula = !name.empty() && std::string("=+-@\t\r").find(name.front()) != std::string::npos;
  return formula ? "'" + name : name;
}

bool starts_formula(const std::string& field) {
  return !field.empty() && std::string("=+-@\t\r").find(field.front()) != std::string::npos;
}

// A timeline row, a memory row (on a host of that name) and a cache row (of a file of that
// name) per hostile name, each in every text column somewhere.
pagecache::RunResult hostile_result() {
  pagecache::RunResult r;
  const std::size_t n = kHostile.size();
  // Names are interned (RunResult::names); the phase is read, compute or write, never a name.
  r.names.assign(kHostile.begin(), kHostile.end());
  r.hosts.assign(kHostile.begin(), kHostile.end());
  for (std::size_t i = 0; i < n; ++i) {
    r.timeline.push_back({static_cast<std::uint32_t>(i), static_cast<std::uint32_t>((i + 1) % n), pagecache::PhaseKind::Write,
                          static_cast<std::uint32_t>((i + 2) % n), 0.5 * static_cast<double>(i), 1.25, 100, 60, -static_cast<std::int64_t>(i)});
    pagecache::MemoryRow m;
    m.time = static_cast<double>(i);
    m.host = static_cast<std::uint32_t>(i);
    m.state.total = 1000;
    m.state.free = -3;
    r.memory.push_back(m);
    r.files.push_back(kHostile[(i + 3) % n]);
    r.cache.push_back({static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(i), static_cast<std::int64_t>(i) * 7});
  }
  return r;
}

}  // namespace

TEST_CASE("CSV fields with commas, quotes and line breaks read back as written, and none starts a formula", "[report][csv]") {
  const fs::path dir = scratch("csv");
  const pagecache::RunResult r = hostile_result();
  write_timeline_csv(dir / "timeline.csv", r);
  write_memory_csv(dir / "memory.csv", r);
  write_cache_csv(dir / "cache.csv", r);
  // Plain names (no special character, not a formula) are written as they are, as ever.
  CHECK_THAT(slurp(dir / "cache.csv"),
             Catch::Contains("\nunicode: n\xC3\xA4me \xE5\x90\x8D \xF0\x9F\x9A\x80,'starts with a quote,write,plain_name,91\n"));
  const Rows timeline = parse_csv(slurp(dir / "timeline.csv"));
  const Rows memory = parse_csv(slurp(dir / "memory.csv"));
  const Rows cache = parse_csv(slurp(dir / "cache.csv"));
  const std::size_t n = kHostile.size();
  REQUIRE(timeline.size() == n + 1);
  REQUIRE(memory.size() == n + 1);
  REQUIRE(cache.size() == n + 1);
  CHECK(timeline[0] == std::vector<std::string>{"app", "task", "host", "phase", "start_s", "end_s", "bytes", "cache_bytes", "disk_bytes"});
  CHECK(memory[0].front() == "host");
  CHECK(cache[0] == std::vector<std::string>{"app", "task", "phase", "file", "cached_bytes"});
  for (std::size_t i = 0; i < n; ++i) {
    INFO("row " << i + 1);
    const auto& t = timeline[i + 1];
    REQUIRE(t.size() == 9);
    CHECK(t[0] == as_written(kHostile[i]));
    CHECK(t[1] == as_written(kHostile[(i + 1) % n]));
    CHECK(t[2] == as_written(kHostile[(i + 2) % n]));  // the host
    CHECK(t[3] == "write");
    // Numbers are never touched: a negative one keeps its sign and gets no quote.
    CHECK(t[4] == fmt::format("{:.6f}", 0.5 * static_cast<double>(i)));
    CHECK(t[5] == "1.250000");
    CHECK(t[8] == fmt::format("{}", -static_cast<std::int64_t>(i)));
    const auto& m = memory[i + 1];
    REQUIRE(m.size() == 10);
    CHECK(m[0] == as_written(kHostile[i]));
    CHECK(m[1] == fmt::format("{:.6f}", static_cast<double>(i)));
    CHECK(m[3] == "-3");
    const auto& c = cache[i + 1];
    REQUIRE(c.size() == 5);
    CHECK(c[0] == t[0]);
    CHECK(c[1] == t[1]);
    CHECK(c[2] == t[3]);
    CHECK(c[3] == as_written(kHostile[(i + 3) % n]));
    CHECK(c[4] == fmt::format("{}", i * 7));
    for (const auto* row : {&t, &m, &c}) {
      for (std::size_t k = 0; k < row->size(); ++k) {
        const bool number_column = row == &t ? k >= 4 : row == &m ? k >= 1 : k == 4;
        if (!number_column) CHECK_FALSE(starts_formula((*row)[k]));
      }
    }
  }
}

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

TEST_CASE("the terminal summary shows control characters in names as escapes", "[report]") {
  pagecache::Scenario s;
  s.source = "dir/\x1B]0;title\x07.toml";
  s.title = "two\nlines";
  pagecache::RunResult r;
  r.names = {"evil\x1B[2J", "t\r"};
  r.timeline.push_back({0, 1, pagecache::PhaseKind::Read, 0, 0.0, 1.0, 0, 0, 0});
  const std::string out = readable_summary(s, r);
  for (char c : out) {
    INFO(out);
    REQUIRE((static_cast<unsigned char>(c) >= 0x20 || c == '\n'));
  }
  CHECK_THAT(out, Catch::StartsWith("two\\nlines\nscenario dir/\\u001b]0;title\\u0007.toml"));
  CHECK_THAT(out, Catch::Contains("app evil\\u001b[2J\n") && Catch::Contains("t\\r"));
}

TEST_CASE("the terminal summary shows a slow phase's rate, not 0.0", "[report]") {
  pagecache::Scenario s;
  pagecache::RunResult r;
  r.names = {"app", "task"};
  r.timeline.push_back({0, 1, pagecache::PhaseKind::Read, 0, 0.0, 6213.0, 100'000'000, 0, 100'000'000});   // 0.0161 MB/s
  r.timeline.push_back({0, 1, pagecache::PhaseKind::Write, 0, 6213.0, 6313.0, 51'234'000'000, 0, 0});     // 512.34 MB/s
  const std::string out = readable_summary(s, r);
  INFO(out);
  CHECK_THAT(out, Catch::Contains(" 0.0161 "));
  CHECK_THAT(out, Catch::Contains(" 512.3 "));
}
