// Sweep files: the runs they make, their ids, and the bad ones refused naming the axis.
#include "support/files.hpp"
#include "sweep/sweep.hpp"
#include "sweep/result_line.hpp"
#include "sweep/results_file.hpp"

#include <pagecache/error.hpp>
#include <pagecache/scenario_file.hpp>

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using pagecache::ConfigError;
using pagecache::sweep::Sweep;
using pagecache::testing::scratch;
using pagecache::testing::slurp;

namespace {

const std::string kBase = fmt::format("scenario = \"{}/scenarios/paper/exp2.toml\"\n", PCSIM_SOURCE_DIR);

fs::path sweep_file(const std::string& name, const std::string& text) {
  const fs::path file = scratch("sweep_" + name) / "sweep.toml";
  std::ofstream(file) << text;
  return file;
}

Sweep plan_of(const std::string& name, const std::string& text) { return Sweep::load(sweep_file(name, text).string()); }

void expect_refused(const std::string& name, const std::string& text, const std::vector<std::string>& fragments) {
  try {
    plan_of(name, text);
    FAIL("accepted: " << text);
  } catch (const ConfigError& e) {
    INFO(e.what());
    CHECK_THAT(e.what(), Catch::Contains("sweep.toml"));
    for (const std::string& f : fragments) CHECK_THAT(e.what(), Catch::Contains(f));
  }
}

std::vector<std::string> ids(const Sweep& plan) {
  std::vector<std::string> out;
  for (std::size_t i = 0; i < plan.size(); ++i) out.push_back(plan.run(i).id);
  return out;
}

}  // namespace

TEST_CASE("a grid sweeps every combination, the last axis fastest", "[sweep]") {
  const Sweep plan = plan_of("grid", kBase + R"(
[[axes]]
key = "pipelines.count"
range = { from = 1, to = 3, step = 1 }
[[axes]]
key = "hosts.0.memory"
values = ["128 GB", "256 GB"]
)");
  REQUIRE(plan.size() == 6);
  CHECK(plan.keys() == std::vector<std::string>{"pipelines.count", "hosts.0.memory"});
  CHECK(plan.run(0).overrides[0].toml == "1");
  CHECK(plan.run(0).overrides[1].toml == "\"128 GB\"");
  CHECK(plan.run(0).overrides[1].shown == "128 GB");
  CHECK(plan.run(1).overrides[1].shown == "256 GB");
  CHECK(plan.run(5).overrides[0].toml == "3");
  const auto all = ids(plan);
  CHECK(std::set<std::string>(all.begin(), all.end()).size() == 6);
  // The run really is the base with its overrides, the platform's host included.
  const pagecache::Scenario s = plan.scenario(plan.run(5));
  CHECK(s.hosts.front().memory == 256'000'000'000);
  CHECK(s.apps.size() == 3);
}

TEST_CASE("a run's id depends on its overrides alone: new axis values and reordered axes rename no run", "[sweep]") {
  const std::string a = R"(
[[axes]]
key = "pipelines.count"
values = [1, 2]
[[axes]]
key = "hosts.0.page_cache.dirty_ratio"
values = [0.2, 0.4]
)";
  const std::string more = R"(
[[axes]]
key = "hosts.0.page_cache.dirty_ratio"
values = [0.1, 0.2, 0.4]
[[axes]]
key = "pipelines.count"
values = [2, 1, 4]
)";
  const auto before = ids(plan_of("ids_a", kBase + a));
  const auto after = ids(plan_of("ids_b", kBase + more));
  CHECK(after.size() == 9);
  for (const std::string& id : before) CHECK(std::find(after.begin(), after.end(), id) != after.end());
  CHECK(before[0] == pagecache::sweep::run_id({{"pipelines.count", "1", "1"}, {"hosts.0.page_cache.dirty_ratio", "0.2", "0.2"}}));
  CHECK(before[0].size() == 16);
}

TEST_CASE("a run is found by its values in a grown grid or among points, and only there", "[sweep]") {
  // The grown sweep of the test above: a result recorded under the first plan is placed by its values.
  const Sweep grown = plan_of("find_grid", kBase + R"(
[[axes]]
key = "hosts.0.page_cache.dirty_ratio"
values = [0.1, 0.2, 0.4]
[[axes]]
key = "pipelines.count"
values = [2, 1, 4]
)");
  for (std::size_t i = 0; i < grown.size(); ++i) {
    std::vector<std::pair<std::string, std::string>> values;
    for (const pagecache::sweep::Override& o : grown.run(i).overrides) values.emplace_back(o.key, o.toml);
    CHECK(grown.index_of(values) == i);
    std::reverse(values.begin(), values.end());  // as a result line lists them: by key, any order
    CHECK(grown.index_of(values) == i);
  }
  CHECK(grown.index_of({{"pipelines.count", "1"}, {"hosts.0.page_cache.dirty_ratio", "0.2"}}) == 4);
  CHECK_FALSE(grown.index_of({{"pipelines.count", "3"}, {"hosts.0.page_cache.dirty_ratio", "0.2"}}));  // not a value of its axis
  CHECK_FALSE(grown.index_of({{"pipelines.count", "1"}}));                                             // a key missing
  CHECK_FALSE(grown.index_of({{"pipelines.count", "1"}, {"hosts.0.page_cache.dirty_ratio", "0.2"}, {"title", "\"x\""}}));  // one too many
  const Sweep points = plan_of("find_points", kBase + R"(
[[points]]
"pipelines.count" = 2
[[points]]
"pipelines.count" = 4
"hosts.0.memory" = "128 GB"
)");
  CHECK(points.index_of({{"pipelines.count", "2"}}) == 0);
  CHECK(points.index_of({{"hosts.0.memory", "\"128 GB\""}, {"pipelines.count", "4"}}) == 1);
  CHECK_FALSE(points.index_of({{"pipelines.count", "4"}}));  // the second point sets the memory too
}

TEST_CASE("ranges: integers, floats without residue, log ranges", "[sweep]") {
  const Sweep floats = plan_of("floats", kBase + R"(
[[axes]]
key = "hosts.0.page_cache.dirty_ratio"
range = { from = 0.1, to = 0.5, step = 0.1 }
)");
  std::vector<std::string> values;
  for (std::size_t i = 0; i < floats.size(); ++i) values.push_back(floats.run(i).overrides[0].toml);
  CHECK(values == std::vector<std::string>{"0.1", "0.2", "0.3", "0.4", "0.5"});
  const Sweep logs = plan_of("logs", kBase + R"(
[[axes]]
key = "pipelines.count"
range = { from = 1, to = 32, factor = 2 }
)");
  values.clear();
  for (std::size_t i = 0; i < logs.size(); ++i) values.push_back(logs.run(i).overrides[0].toml);
  CHECK(values == std::vector<std::string>{"1", "2", "4", "8", "16", "32"});
}

TEST_CASE("explicit points set only what they name", "[sweep]") {
  const Sweep plan = plan_of("points", kBase + R"(
[[points]]
"pipelines.count" = 2
[[points]]
"pipelines.count" = 4
"hosts.0.memory" = "128 GB"
)");
  REQUIRE(plan.size() == 2);
  CHECK(plan.keys() == std::vector<std::string>{"pipelines.count", "hosts.0.memory"});
  CHECK(plan.run(0).overrides[1].toml.empty());
  CHECK(plan.scenario(plan.run(0)).hosts.front().memory == 268'000'000'000);
  CHECK(plan.scenario(plan.run(1)).hosts.front().memory == 128'000'000'000);
  // The plan as sweep-plan.json holds it makes the same runs.
  const Sweep again = Sweep::from_json(plan.json(), "test");
  CHECK(ids(again) == ids(plan));
  CHECK(again.run(1).overrides[1].shown == "128 GB");
}

TEST_CASE("bad sweep files are refused, naming the axis", "[sweep][errors]") {
  expect_refused("unknown_key", kBase + "colour = 3\n[[axes]]\nkey = \"pipelines.count\"\nvalues = [1]\n", {"unknown key 'colour'"});
  expect_refused("unknown_axis_key", kBase + "[[axes]]\nkey = \"pipelines.colour\"\nvalues = [1]\n", {"axis 'pipelines.colour'", "colour"});
  expect_refused("empty", kBase + "[[axes]]\nkey = \"pipelines.count\"\nvalues = []\n", {"axis 'pipelines.count' has no value"});
  expect_refused("wrong_type", kBase + "[[axes]]\nkey = \"hosts.0.memory\"\nvalues = [\"64 GB\", true]\n", {"axis 'hosts.0.memory'", "value true"});
  expect_refused("step_zero", kBase + "[[axes]]\nkey = \"pipelines.count\"\nrange = { from = 1, to = 4, step = 0 }\n",
                 {"axis 'pipelines.count'", "step cannot be 0"});
  expect_refused("never_reaches", kBase + "[[axes]]\nkey = \"pipelines.count\"\nrange = { from = 4, to = 1, step = 1 }\n",
                 {"axis 'pipelines.count'", "never reaches"});
  expect_refused("twice", kBase + "[[axes]]\nkey = \"pipelines.count\"\nvalues = [1, 2, 1]\n", {"axis 'pipelines.count'", "twice"});
  expect_refused("no_axes", kBase, {"[[axes]]", "[[points]]"});
  // 30 x 3001 x 1000 runs: refused without --force, naming the axes, before any run is made.
  const std::string huge = kBase + "[[axes]]\nkey = \"pipelines.count\"\nrange = { from = 1, to = 30, step = 1 }\n"
                                   "[[axes]]\nkey = \"hosts.0.page_cache.dirty_ratio\"\nrange = { from = 0.1, to = 0.4, step = 0.0001 }\n"
                                   "[[axes]]\nkey = \"pipelines.cpu_time\"\nrange = { from = 1, to = 1000, step = 1 }\n";
  expect_refused("huge", huge, {"90030000 runs", "axis 'pipelines.count' 30 x", "--force"});
  CHECK(Sweep::load(sweep_file("huge_forced", huge).string(), true).size() == 90'030'000);
}

TEST_CASE("a range's length is computed before its values are made; one that is not a finite number says so", "[sweep][errors]") {
  const auto range = [](const std::string& r) { return kBase + "[[axes]]\nkey = \"pipelines.count\"\nrange = { " + r + " }\n"; };
  // 34657361 steps: refused at once, not after making them (10 s and 1.6 GB before).
  expect_refused("factor_tiny", range("from = 1, to = 32, factor = 1.0000001"),
                 {"axis 'pipelines.count'", "by factor 1.0000001 makes 34657361 values", "more than an axis may have (10000000)"});
  expect_refused("step_tiny", range("from = 0.0, to = 1.0, step = 1e-300"), {"axis 'pipelines.count'", "more than an axis may have"});
  expect_refused("step_nan", range("from = 1, to = 4, step = nan"), {"axis 'pipelines.count'", "step = nan is not a number"});
  expect_refused("step_inf", range("from = 1, to = 4, step = inf"), {"step = inf is not a finite number"});
  expect_refused("from_nan", range("from = nan, to = 4, step = 1"), {"from = nan is not a number"});
  expect_refused("to_inf", range("from = 1, to = -inf, step = 1"), {"to = -inf is not a finite number"});
  expect_refused("factor_nan", range("from = 1, to = 4, factor = nan"), {"factor = nan is not a number"});
  expect_refused("factor_inf", range("from = 1, to = 4, factor = inf"), {"factor = inf is not a finite number"});
  expect_refused("factor_one", range("from = 1, to = 4, factor = 1"), {"factor = 1 never leaves 1"});
  expect_refused("factor_zero", range("from = 1, to = 4, factor = 0"), {"factor = 0 must be above 0"});
  expect_refused("factor_negative", range("from = 1, to = 4, factor = -2"), {"factor = -2 must be above 0"});
  // Three axes of a million values each: refused by their product, before any is made.
  const std::string cube = kBase + "[[axes]]\nkey = \"pipelines.count\"\nrange = { from = 1, to = 1000000, step = 1 }\n"
                                   "[[axes]]\nkey = \"pipelines.cpu_time\"\nrange = { from = 1, to = 1000000, step = 1 }\n"
                                   "[[axes]]\nkey = \"hosts.0.page_cache.dirty_ratio\"\nrange = { from = 0.000001, to = 1.0, step = 0.000001 }\n";
  expect_refused("cube", cube, {"more than pcsim can number"});
}

TEST_CASE("a results file drops a partial last line and knows the runs it holds", "[sweep]") {
  const fs::path file = scratch("sweep_results") / "results-0-of-1.jsonl";
  const std::string base = "0123456789abcdef";
  const auto line = [&](const char* count) {
    pagecache::sweep::Run run;
    run.overrides = {{"pipelines.count", count, count}};
    run.id = pagecache::sweep::run_id(run.overrides);
    return pagecache::sweep::result_line(base, run, nullptr, 2, "refused", 0.5);
  };
  const std::string a = line("1"), b = line("2"), c = line("3");
  std::ofstream(file) << a << "\n" << b << "\n" << c.substr(0, 40);
  {
    pagecache::sweep::ResultsFile results(file.string(), base);
    CHECK(results.done().size() == 2);
    results.append(c);
    // A second writer of the same shard is refused while the first holds it.
    CHECK_THROWS_AS(pagecache::sweep::ResultsFile(file.string(), base), ConfigError);
  }
  CHECK(slurp(file) == a + "\n" + b + "\n" + c + "\n");
  std::ofstream(file, std::ios::app) << "not json\n";
  CHECK_THROWS_WITH(pagecache::sweep::ResultsFile(file.string(), base), Catch::Contains("results-0-of-1.jsonl:4: not a result"));
}

TEST_CASE("overrides of hosts keys reach the TOML platform file a scenario takes them from, and only for that run", "[sweep][scenario]") {
  const std::string exp2 = std::string(PCSIM_SOURCE_DIR) + "/scenarios/paper/exp2.toml";
  const pagecache::Scenario changed = pagecache::load_scenario(exp2, {{"hosts.0.memory", "\"64 GB\""}, {"hosts.1.cores", "4"}});
  CHECK(changed.hosts.at(0).memory == 64'000'000'000);
  CHECK(changed.hosts.at(1).cores == 4);
  CHECK(pagecache::load_scenario(exp2).hosts.at(0).memory == 268'000'000'000);
  // A value of the wrong type names the option.
  CHECK_THROWS_WITH(pagecache::load_scenario(exp2, {{"hosts.0.memory", "true"}}), Catch::Contains("hosts[0].memory"));
  // A SimGrid platform's hosts are amended by name, not by --set.
  const fs::path dir = scratch("sweep_xml_platform");
  std::ofstream(dir / "s.toml") << fmt::format("platform = \"{}/inputs/wrench-cache/single_host.xml\"\n", PCSIM_SOURCE_DIR);
  CHECK_THROWS_WITH(pagecache::load_scenario((dir / "s.toml").string(), {{"hosts.0.memory", "\"64 GB\""}}),
                    Catch::Contains("SimGrid platform file") && Catch::Contains("[[hosts]]"));
}
