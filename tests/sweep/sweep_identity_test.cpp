// A sweep folder belongs to one sweep: its results files are read whole before pcsim changes a
// byte of them, lines of another base (or of this base edited since) are refused naming what
// changed, and a run recorded in any results file is done, whatever the shard split.
#include "support/files.hpp"
#include "sweep_property.hpp"
#include "sweep/executor.hpp"
#include "sweep/merge.hpp"
#include "sweep/sweep.hpp"
#include "sweep/result_line.hpp"
#include "sweep/results_file.hpp"

#include <pagecache/error.hpp>
#include <pagecache/run.hpp>

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <regex>
#include <string>
#include <sys/stat.h>

namespace fs = std::filesystem;
using pagecache::ConfigError;
using pagecache::sweep::Sweep;
using pagecache::testing::scratch;
using pagecache::testing::slurp;

namespace {

const std::string kFingerprint = "0123456789abcdef";

pagecache::sweep::Run run_of(const std::string& key, const std::string& toml) {
  pagecache::sweep::Run run;
  run.index = 7;
  run.overrides = {{key, toml, toml}};
  run.id = pagecache::sweep::run_id(run.overrides);
  return run;
}

// A line of a run that ended well, with figures of every width, and of one that failed with an
// error of quotes, control characters and UTF-8.
std::string ok_line(const std::string& count = "3") {
  pagecache::RunResult result;
  result.summary.makespan = 22.76882;
  result.summary.end_time = 64.354839;
  result.summary.disk_read_bytes = 3'000'000'000;
  result.summary.events = 577;
  result.summary.wall_seconds = 0.000104;
  return pagecache::sweep::result_line(kFingerprint, run_of("pipelines.count", count), &result, 0, {}, 0.25);
}

std::string failed_line() {
  return pagecache::sweep::result_line(kFingerprint, run_of("hosts.0.memory", "\"64 GB\""), nullptr, 2,
                                       "a \"quoted\" error\twith é and 日本 and \\ and \x01", 1.5);
}

fs::path results_with(const std::string& name, const std::string& bytes) {
  const fs::path file = scratch(name) / "results-0-of-1.jsonl";
  std::ofstream(file, std::ios::binary) << bytes;
  return file;
}

// `file` is refused with a message holding `fragment`, and is still `bytes`.
void refused_untouched(const fs::path& file, const std::string& bytes, const std::string& fragment) {
  try {
    pagecache::sweep::ResultsFile results(file.string(), kFingerprint);
    FAIL("accepted: " << file);
  } catch (const ConfigError& e) {
    CHECK_THAT(e.what(), Catch::Contains(fragment));
  }
  CHECK(slurp(file) == bytes);
}

// A base of its own, in a scratch folder: the paper's Exp 2 with its platforms beside it, so
// that a test may edit them.
struct Base {
  fs::path dir;
  explicit Base(const std::string& name) : dir(scratch(name)) {
    const std::string source = PCSIM_SOURCE_DIR;
    fs::copy_file(source + "/platforms/wrench-cache.toml", dir / "wrench-cache.toml");
    fs::copy_file(source + "/platforms/paper-cluster.toml", dir / "paper-cluster.toml");
    std::string text = slurp(source + "/scenarios/paper/exp2.toml");
    text = std::regex_replace(text, std::regex("\\.\\./\\.\\./platforms/"), "");
    std::ofstream(dir / "base.toml") << text;
  }
  // A sweep of pipelines.count over `values`, on base.toml (or `scenario`).
  std::string sweep(const std::string& name, const std::string& values, const std::string& extra = {}, const std::string& scenario = "base.toml") const {
    const fs::path file = dir / (name + ".toml");
    std::ofstream(file) << fmt::format("scenario = \"{}\"\n{}[[axes]]\nkey = \"pipelines.count\"\nvalues = [{}]\n", scenario, extra, values);
    return file.string();
  }
  void edit(const std::string& file, const std::string& from, const std::string& to) const {
    const std::string text = slurp(dir / file);
    REQUIRE(text.find(from) != std::string::npos);
    std::ofstream(dir / file) << std::regex_replace(text, std::regex(from), to);
  }
  std::string out(const std::string& name) const { return (dir / name).string(); }
};

pagecache::sweep::SweepOutcome run(const std::string& sweep, const std::string& out, const std::string& shard = "0/1") {
  pagecache::sweep::SweepOptions options;
  options.out_dir = out;
  options.shard = pagecache::sweep::parse_shard(shard);
  return pagecache::sweep::run_sweep(Sweep::load(sweep), options);
}

// Every file of a folder and its bytes.
std::map<std::string, std::string> contents(const fs::path& dir) {
  std::map<std::string, std::string> out;
  for (const auto& entry : fs::directory_iterator(dir)) out[entry.path().filename().string()] = slurp(entry.path());
  return out;
}

std::string refusal(const std::function<void()>& what) {
  try {
    what();
  } catch (const ConfigError& e) {
    return e.what();
  }
  FAIL("not refused");
  return {};
}

}  // namespace

TEST_CASE("the lines pcsim writes read back as results of their sweep, and only of theirs", "[sweep]") {
  for (const std::string& line : {ok_line(), failed_line()}) {
    INFO(line);
    const auto check = pagecache::sweep::check_result_line(line, kFingerprint);
    CHECK(check.problem.empty());
    CHECK(check.id.size() == 16);
    CHECK_THAT(pagecache::sweep::check_result_line(line, "fedcba9876543210").problem, Catch::Contains("another sweep"));
  }
  // A line of the pcsim before fingerprints, an id that is not its overrides', a member more.
  const std::string old = std::regex_replace(ok_line(), std::regex("\"base\": \"[0-9a-f]+\", "), "");
  CHECK_THAT(pagecache::sweep::check_result_line(old, kFingerprint).problem, Catch::Contains("\"run\" where pcsim writes \"base\""));
  const std::string other_id = std::regex_replace(ok_line(), std::regex("\"pipelines.count\": \"3\""), "\"pipelines.count\": \"4\"");
  CHECK_THAT(pagecache::sweep::check_result_line(other_id, kFingerprint).problem, Catch::Contains("is not that of its overrides"));
  const std::string more = ok_line().substr(0, ok_line().size() - 1) + ", \"x\": 1}";
  CHECK_THAT(pagecache::sweep::check_result_line(more, kFingerprint).problem, Catch::Contains("\"x\" after \"sim_wall_s\""));
  std::string spaced = ok_line();
  spaced.insert(spaced.begin(), ' ');
  CHECK_FALSE(pagecache::sweep::check_result_line(spaced, kFingerprint).problem.empty());
}

TEST_CASE("every beginning of a line pcsim writes may be dropped as cut short, and other last lines may not", "[sweep]") {
  for (const std::string& line : {ok_line("123"), failed_line()}) {
    for (std::size_t n = 1; n <= line.size(); ++n) {
      INFO(line.substr(0, n));
      CHECK(pagecache::sweep::check_cut_result_line(line.substr(0, n), kFingerprint).problem == "");
    }
  }
  const auto cut = [](const std::string& partial) { return pagecache::sweep::check_cut_result_line(partial, kFingerprint).problem; };
  CHECK_FALSE(cut("world").empty());
  CHECK_FALSE(cut(" {\"id\"").empty());
  CHECK_FALSE(cut("{\"run\": 1").empty());
  CHECK_FALSE(cut("{\"id\": \"0123\", ").empty());           // not 16 hex digits
  CHECK_FALSE(cut("{\"id\": \"a9b35286ab680f3f\", \"base\": \"fedcba9876543210\"").empty());  // another sweep's
  // "makespan_s": 22 is the beginning of 22.768820, "makespan_s": 22, is not.
  const std::string line = ok_line();
  const std::size_t at = line.find("22.76");
  CHECK(cut(line.substr(0, at + 2)).empty());
  CHECK_FALSE(cut(line.substr(0, at + 2) + ",").empty());
}

TEST_CASE("a results file is checked whole before any repair: what pcsim did not write is refused, untouched", "[sweep]") {
  refused_untouched(results_with("sweep_hello", "hello\nworld"), "hello\nworld", "results-0-of-1.jsonl:1: not a result pcsim wrote");
  const std::string line = ok_line();
  refused_untouched(results_with("sweep_world", line + "\nworld"), line + "\nworld", "results-0-of-1.jsonl:2: a last line without its newline");
  const std::string old = std::regex_replace(line, std::regex("\"base\": \"[0-9a-f]+\", "), "");
  refused_untouched(results_with("sweep_old", line + "\n" + old + "\n"), line + "\n" + old + "\n", ":2: not a result pcsim wrote");
  const std::string other = std::regex_replace(line, std::regex(kFingerprint), "fedcba9876543210");
  refused_untouched(results_with("sweep_other", other + "\n"), other + "\n", ":1: the result of a run of another sweep");
  // The one repair: a last line that is the beginning of pcsim's.
  const fs::path file = results_with("sweep_cut", line + "\n" + failed_line().substr(0, 50));
  {
    const pagecache::sweep::ResultsFile results(file.string(), kFingerprint);
    CHECK(results.done().size() == 1);
  }
  CHECK(slurp(file) == line + "\n");
}

TEST_CASE("a results file that is a link, a file of two names or not a regular file is refused untouched, naming it", "[sweep]") {
  const fs::path dir = scratch("sweep_not_pcsims");
  const std::string bytes = ok_line() + "\n" + ok_line("4").substr(0, 30);  // a partial last line pcsim would drop from its own file
  std::ofstream(dir / "elsewhere.jsonl") << bytes;
  const fs::path link = dir / "results-0-of-2.jsonl";
  fs::create_symlink(dir / "elsewhere.jsonl", link);
  const fs::path hard = dir / "results-1-of-2.jsonl";
  fs::create_hard_link(dir / "elsewhere.jsonl", hard);
  const fs::path fifo = dir / "results-0-of-3.jsonl";
  REQUIRE(::mkfifo(fifo.c_str(), 0644) == 0);
  const fs::path folder = dir / "results-1-of-3.jsonl";
  fs::create_directory(folder);
  for (const auto& [path, why] : {std::pair{link, "is a symbolic link"}, std::pair{hard, "has 2 hard links"},
                                  std::pair{fifo, "is not a regular file"}, std::pair{folder, "is a folder"}}) {
    INFO(path);
    for (const std::string& message : {refusal([&] { pagecache::sweep::ResultsFile(path.string(), kFingerprint); }),
                                       refusal([&] { pagecache::sweep::read_results_file(path.string()); })}) {
      CHECK_THAT(message, Catch::Contains(path.string()) && Catch::Contains(why) && Catch::Contains("left as it is"));
    }
  }
  CHECK(fs::is_symlink(link));
  CHECK(slurp(dir / "elsewhere.jsonl") == bytes);
  CHECK(fs::hard_link_count(hard) == 2);
}

TEST_CASE("a results file copied from another sweep's folder is refused by merge and by run, naming it", "[sweep]") {
  const Base base("sweep_copied");
  std::ofstream(base.dir / "other.toml") << std::regex_replace(slurp(base.dir / "base.toml"), std::regex("4.4 s"), "5 s");
  run(base.sweep("a", "1, 2"), base.out("A"));
  run(base.sweep("b", "1, 2", {}, "other.toml"), base.out("B"));
  fs::rename(base.dir / "B" / "results-0-of-1.jsonl", base.dir / "A" / "results-0-of-2.jsonl");
  fs::remove(base.dir / "A" / "results-0-of-1.jsonl");
  const auto before = contents(base.dir / "A");
  const std::string merged = refusal([&] { pagecache::sweep::merge({base.out("A"), {}, false}); });
  CHECK_THAT(merged, Catch::Contains("results-0-of-2.jsonl:1: the result of a run of another sweep"));
  const std::string ran = refusal([&] { run(base.sweep("a", "1, 2"), base.out("A")); });
  CHECK_THAT(ran, Catch::Contains("results-0-of-2.jsonl:1: the result of a run of another sweep"));
  CHECK(contents(base.dir / "A") == before);
}

TEST_CASE("a base edited since the folder's runs is refused, naming the file; a file the profile does not read is no part of it", "[sweep]") {
  const Base base("sweep_edited");
  run(base.sweep("a", "1, 2"), base.out("C"));
  const auto before = contents(base.dir / "C");
  // The linux profile's platform is not the paper profile's base.
  base.edit("paper-cluster.toml", "\n", "\n# edited\n");
  CHECK(run(base.sweep("a", "1, 2"), base.out("C")).skipped == 2);
  base.edit("base.toml", "4.4 s", "9 s");
  std::string message = refusal([&] { run(base.sweep("grown", "1, 2, 3"), base.out("C")); });
  CHECK_THAT(message, Catch::Contains("another base scenario") && Catch::Contains((base.dir / "base.toml").string() + " (the scenario file) has changed"));
  CHECK(contents(base.dir / "C") == before);
  base.edit("base.toml", "9 s", "4.4 s");
  base.edit("wrench-cache.toml", "\n", "\n# edited\n");
  message = refusal([&] { run(base.sweep("grown", "1, 2, 3"), base.out("C")); });
  CHECK_THAT(message, Catch::Contains((base.dir / "wrench-cache.toml").string() + " (the platform file) has changed"));
  CHECK(contents(base.dir / "C") == before);
  // Another profile reads another platform file.
  message = refusal([&] { run(base.sweep("linux", "1, 2", "profile = \"linux\"\n"), base.out("C")); });
  CHECK_THAT(message, Catch::Contains("paper-cluster.toml, not") && Catch::Contains("the settings are 'profile = linux', not 'none'"));
  CHECK(contents(base.dir / "C") == before);
}

TEST_CASE("the same base moved elsewhere is the same base", "[sweep]") {
  const Base base("sweep_moved");
  run(base.sweep("a", "1, 2"), base.out("D"));
  const fs::path moved = scratch("sweep_moved_to");
  for (const char* f : {"base.toml", "wrench-cache.toml", "paper-cluster.toml", "a.toml"}) fs::copy_file(base.dir / f, moved / f);
  pagecache::sweep::SweepOptions options;
  options.out_dir = base.out("D");
  const auto outcome = pagecache::sweep::run_sweep(Sweep::load((moved / "a.toml").string()), options);
  CHECK(outcome.ran == 0);
  CHECK(outcome.skipped == 2);
}

TEST_CASE("any mix of shard splits over a folder's life runs each run once", "[sweep]") {
  const Base base("sweep_splits");
  for (const char* shard : {"0/3", "1/3", "2/3"}) run(base.sweep("s3", "1, 2, 3"), base.out("E"), shard);
  auto outcome = run(base.sweep("s4", "1, 2, 3, 4"), base.out("E"));
  CHECK(outcome.ran == 1);
  CHECK(outcome.skipped == 3);
  CHECK(pagecache::sweep::merge({base.out("E"), {}, false}).runs == 4);
  // Another split again: shard 1/2 of five runs holds runs 2 and 4, both done.
  outcome = run(base.sweep("s5", "1, 2, 3, 4, 5"), base.out("E"), "1/2");
  CHECK(outcome.ran == 0);
  CHECK(outcome.skipped == 2);
  outcome = run(base.sweep("s5", "1, 2, 3, 4, 5"), base.out("E"), "0/2");
  CHECK(outcome.ran == 1);
  CHECK(outcome.skipped == 2);
  CHECK(pagecache::sweep::merge({base.out("E"), {}, false}).runs == 5);
}

TEST_CASE("another shard's file is read, never repaired", "[sweep]") {
  const Base base("sweep_other_shard");
  run(base.sweep("s2", "1, 2, 3"), base.out("F"), "0/2");
  const fs::path other = base.dir / "F" / "results-0-of-2.jsonl";
  std::ofstream(other, std::ios::app) << "{\"id\": \"a9b";  // as if shard 0/2 were writing now
  const std::string bytes = slurp(other);
  CHECK(run(base.sweep("s2", "1, 2, 3"), base.out("F"), "1/2").ran == 1);
  CHECK(slurp(other) == bytes);
}

TEST_CASE("a folder of an earlier pcsim, or whose plan is a link, is refused untouched", "[sweep]") {
  const Base base("sweep_earlier");
  run(base.sweep("a", "1, 2"), base.out("G"));
  const fs::path plan = base.dir / "G" / "sweep-plan.json";
  const std::string without_base = std::regex_replace(slurp(plan), std::regex("\n \"base\": .*\n"), "\n");
  REQUIRE(without_base != slurp(plan));
  std::ofstream(plan) << without_base;
  auto before = contents(base.dir / "G");
  CHECK_THAT(refusal([&] { run(base.sweep("b", "1, 2, 3"), base.out("G")); }), Catch::Contains("an earlier pcsim"));
  CHECK(contents(base.dir / "G") == before);
  fs::rename(plan, base.dir / "plan.json");
  fs::create_symlink(base.dir / "plan.json", plan);
  CHECK_THAT(refusal([&] { run(base.sweep("a", "1, 2"), base.out("G")); }), Catch::Contains("sweep-plan.json is a symbolic link"));
  CHECK(fs::is_symlink(plan));
}

TEST_CASE("sweep merge --csv names its option", "[sweep]") {
  const Base base("sweep_csv");
  run(base.sweep("a", "1, 2"), base.out("H"));
  const fs::path folder = base.dir / "a-folder";
  fs::create_directory(folder);
  CHECK_THAT(refusal([&] { pagecache::sweep::merge({base.out("H"), folder.string(), false}); }),
             Catch::StartsWith(fmt::format("--csv {}: is a folder", folder.string())));
}

TEST_CASE("the sweep fuzzer's seeds keep the sweep readers' contracts", "[sweep][fuzz]") {
  // Read as the fuzzer reads them (fuzz/sweep_fuzzer.cpp): sweep files as if in scenarios/sweeps/.
  const std::string source_name = std::string(PCSIM_SOURCE_DIR) + "/scenarios/sweeps/fuzz.toml";
  std::vector<fs::path> sweeps, results;
  for (const auto& entry : fs::directory_iterator(std::string(PCSIM_SOURCE_DIR) + "/scenarios/sweeps")) sweeps.push_back(entry.path());
  for (const auto& entry : fs::directory_iterator(std::string(PAGECACHE_FUZZ_SEEDS_DIR) + "/sweep-files")) sweeps.push_back(entry.path());
  for (const auto& entry : fs::directory_iterator(PAGECACHE_FUZZ_SEEDS_DIR)) {
    if (entry.path().filename().string().rfind("sweep-results-", 0) == 0) results.push_back(entry.path());
  }
  REQUIRE(sweeps.size() >= 4);
  REQUIRE(results.size() >= 2);
  for (const fs::path& file : sweeps) {
    INFO(file);
    const std::string text = slurp(file);
    CHECK(pagecache::fuzz::check_sweep_text(text, source_name) == "");
    CHECK_NOTHROW(Sweep::parse(text, source_name, false, pagecache::fuzz::sweep_fuzz_limits()));  // a plan, not a refusal
  }
  for (const fs::path& file : results) {
    INFO(file);
    const std::string bytes = slurp(file);
    CHECK(pagecache::fuzz::check_results_bytes(bytes) == "");
    CHECK_NOTHROW(pagecache::sweep::read_results_text(bytes, pagecache::fuzz::kFuzzResultsBase, file.string()));
  }
  // Inputs the fuzzer found (tests/fuzz/regressions/sweep-*): each keeps the contract now, and
  // is refused as results pcsim did not write.
  std::size_t found = 0;
  for (const auto& entry : fs::directory_iterator(PAGECACHE_FUZZ_REGRESSIONS_DIR)) {
    if (entry.path().filename().string().rfind("sweep-results-", 0) != 0) continue;
    ++found;
    INFO(entry.path());
    const std::string bytes = slurp(entry.path());
    CHECK(pagecache::fuzz::check_results_bytes(bytes) == "");
    CHECK_THROWS_AS(pagecache::sweep::read_results_text(bytes, pagecache::fuzz::kFuzzResultsBase, "r.jsonl"), pagecache::ConfigError);
  }
  CHECK(found >= 1);
  // The fuzzer's limits hold: an axis beyond them is refused, not made.
  const std::string long_axis = slurp(std::string(PCSIM_SOURCE_DIR) + "/scenarios/sweeps/exp2.toml") +
                                "[[axes]]\nkey = \"pipelines.cpu_time\"\nrange = { from = 1, to = 100000, step = 1 }\n";
  CHECK_THROWS_WITH(Sweep::parse(long_axis, source_name, false, pagecache::fuzz::sweep_fuzz_limits()),
                    Catch::Contains("makes 100000 values, more than an axis may have (10000)"));
}
