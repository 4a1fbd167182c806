// Applications that wait for others (AppSpec::after, `after = [...]` in [[apps]]): one starts
// when the last it names has ended; the others still start at 0; names must be of
// applications listed before it, one each.
#include <pagecache/error.hpp>
#include <pagecache/run.hpp>
#include <pagecache/scenario.hpp>
#include <pagecache/scenario_file.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <string>

namespace pagecache {
namespace {

const char* const kHost = R"(
[[hosts]]
name = "node"
cores = 4
memory = "8 GB"
memory_read_bw = "6 GB/s"
memory_write_bw = "3 GB/s"
[[hosts.disks]]
name = "disk"
read_bw = "500 MB/s"
write_bw = "400 MB/s"
[[files]]
name = "a"
size = "500 MB"
[[files]]
name = "b"
size = "1 GB"
)";

// Three applications: "short" reads a (1 s), "long" reads b (2 s), "last" computes 1 s after both.
std::string three_apps(const std::string& last_after) {
  return std::string(kHost) + R"(
[[apps]]
name = "short"
[[apps.tasks]]
name = "t"
read = ["a"]
[[apps]]
name = "long"
[[apps.tasks]]
name = "t"
read = ["b"]
[[apps]]
name = "last"
after = )" + last_after + R"(
[[apps.tasks]]
name = "t"
compute = "1 s"
)";
}

// Where application `app`'s first phase starts and its last ends.
std::pair<double, double> span_of(const RunResult& r, const std::string& app) {
  double start = 1e300;
  double end = 0.0;
  for (const PhaseRow& row : r.timeline) {
    if (r.names[row.app] != app) continue;
    start = std::min(start, row.start);
    end = std::max(end, row.end);
  }
  return {start, end};
}

}  // namespace

TEST_CASE("An application with `after` starts when the last it names has ended", "[run][apps]") {
  const RunResult r = run_scenario(parse_scenario(three_apps(R"(["short", "long"])"), "<test>"));
  const auto [short_start, short_end] = span_of(r, "short");
  const auto [long_start, long_end] = span_of(r, "long");
  const auto [last_start, last_end] = span_of(r, "last");
  CHECK(short_start == 0.0);
  CHECK(long_start == 0.0);
  CHECK(short_end < long_end);
  CHECK(last_start == long_end);
  CHECK(last_end == Approx(long_end + 1.0));
}

TEST_CASE("An application waiting for one that ends early does not wait for the others", "[run][apps]") {
  const RunResult r = run_scenario(parse_scenario(three_apps(R"(["short"])"), "<test>"));
  CHECK(span_of(r, "last").first == span_of(r, "short").second);
  CHECK(span_of(r, "last").first < span_of(r, "long").second);
}

TEST_CASE("Without `after` every application starts at 0", "[run][apps]") {
  const RunResult r = run_scenario(parse_scenario(three_apps("[]"), "<test>"));
  CHECK(span_of(r, "last").first == 0.0);
}

TEST_CASE("`after` names applications listed before, one each", "[scenario][apps]") {
  CHECK_THROWS_WITH(parse_scenario(three_apps(R"(["nobody"])"), "x.toml"),
                    Catch::Contains("apps[2].after") && Catch::Contains("'nobody', which is not an application listed before it"));
  // A later application cannot be waited for: no order could have a cycle.
  std::string later = three_apps("[]");
  later.replace(later.find("name = \"short\"\n"), 15, "name = \"short\"\nafter = [\"last\"]\n");
  CHECK_THROWS_WITH(parse_scenario(later, "x.toml"), Catch::Contains("apps[0].after") && Catch::Contains("'last'"));
  std::string twice = three_apps(R"(["t2"])");
  twice.replace(twice.find("name = \"short\""), 14, "name = \"t2\"");
  twice.replace(twice.find("name = \"long\""), 13, "name = \"t2\"");
  CHECK_THROWS_WITH(parse_scenario(twice, "x.toml"), Catch::Contains("names 2 applications listed before it"));
}

TEST_CASE("`after` is shown, and what is shown reads back", "[scenario][apps]") {
  const Scenario s = parse_scenario(three_apps(R"(["short", "long"])"), "<test>");
  const std::string shown = to_toml(s);
  CHECK_THAT(shown, Catch::Contains(R"(after = [ "short", "long" ])"));
  CHECK(parse_scenario(shown, "<shown>").apps[2].after == std::vector<std::string>{"short", "long"});
}

}  // namespace pagecache
