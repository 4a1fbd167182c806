// Every figure the README quotes from pcsim's results, recomputed by running pcsim as a user
// would: the README cannot drift from what the commands print. A figure is compared at the
// precision the README writes it ("12.2" to one decimal, "209" to the unit). Measured speeds
// are not in the README: they measure the machine (docs/performance.md keeps them, dated).

#include "support/child_process.hpp"
#include "support/csv.hpp"
#include "support/files.hpp"
#include "support/pcsim_cli.hpp"

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;
using pagecache::testing::json_field;
using pagecache::testing::read_csv;
using pagecache::testing::slurp;
using pagecache::testing::run_child;
using pagecache::testing::validation_file;

namespace {

// The README's prose with every run of white space made one space (lines wrap anywhere).
std::string readme() {
  return std::regex_replace(slurp(fs::path(PCSIM_SOURCE_DIR) / "README.md"), std::regex(R"(\s+)"), " ");
}

// The figures `pattern`'s groups capture in the README. It is matched from each place its
// leading literal text stands, within a paragraph's length: libstdc++'s regex recurses once per
// character a `.*` crosses, which over the whole README overflows a sanitizer build's stack.
std::vector<std::string> figures(const std::string& pattern) {
  const std::string text = readme();
  const std::string lead = pattern.substr(0, pattern.find_first_of(R"(\()[].*+?{|^$)"));
  const std::regex re(pattern);
  INFO("README pattern: " << pattern);
  std::smatch m;
  std::string window;
  bool found = false;
  for (std::size_t at = text.find(lead); at != std::string::npos && !found; at = lead.empty() ? std::string::npos : text.find(lead, at + 1)) {
    window = lead.empty() ? text : text.substr(at, 2000);
    found = std::regex_search(window, m, re);
  }
  REQUIRE(found);
  std::vector<std::string> out;
  for (std::size_t i = 1; i < m.size(); ++i) out.push_back(m[i].str());
  return out;
}

// `value` written at the precision of `quoted` equals `quoted`.
void check_figure(const std::string& what, const std::string& quoted, double value) {
  const auto dot = quoted.find('.');
  const int decimals = dot == std::string::npos ? 0 : static_cast<int>(quoted.size() - dot - 1);
  INFO(what << ": the README says " << quoted << ", pcsim gives " << value);
  CHECK(fmt::format("{:.{}f}", value, decimals) == quoted);
}

std::string run_pcsim(const std::vector<std::string>& args) {
  std::vector<std::string> argv{PCSIM_BINARY};
  argv.insert(argv.end(), args.begin(), args.end());
  const auto r = run_child(argv, 600.0);
  INFO(r.output);
  REQUIRE(r.status == 0);
  return r.output;
}

// A path for outputs that does not exist yet.
fs::path fresh(const std::string& name) {
  const fs::path dir = pagecache::testing::scratch(name);
  fs::remove(dir);
  return dir;
}


double duration(const pagecache::testing::CsvRow& row) { return std::stod(row.at("end_s")) - std::stod(row.at("start_s")); }

}  // namespace

TEST_CASE("the README's validation figures are what pcsim validate prints", "[cli][docs][validate]") {
  const fs::path dir = pagecache::testing::scratch("validate");
  run_pcsim({"validate", "--json", (dir / "v.json").string(), "--report", (dir / "v.html").string()});
  const std::string json = slurp(dir / "v.json");
  const auto f = figures(
      R"(mean error \(WRENCH-cache's in brackets\): Exp 1 20 GB ([0-9.]+) % \(([0-9.]+) %\), 100 GB ([0-9.]+) % \(([0-9.]+) %\); )"
      R"(Exp 2 read ([0-9.]+) % \(([0-9.]+) %\), write ([0-9.]+) % \(([0-9.]+) %\); Exp 3 read ([0-9.]+) % \(([0-9.]+) %\), )"
      R"(write ([0-9.]+) % \(([0-9.]+) %\)\. Exp 1's dirty memory at every phase end is within ([0-9.]+) % of memory of the real )"
      R"(runs', its cached memory within ([0-9.]+) %\.)");
  REQUIRE(f.size() == 14);
  auto field = [&](const char* c, const char* key) { return json_field(json, c, key); };
  check_figure("Exp 1 20 GB", f[0], field("exp1_20gb", "mean_error_pct"));
  check_figure("Exp 1 20 GB, WRENCH-cache", f[1], field("exp1_20gb", "wrench_cache_mean_error_pct"));
  check_figure("Exp 1 100 GB", f[2], field("exp1_100gb", "mean_error_pct"));
  check_figure("Exp 1 100 GB, WRENCH-cache", f[3], field("exp1_100gb", "wrench_cache_mean_error_pct"));
  check_figure("Exp 2 read", f[4], field("exp2_local", "read_mean_error_pct"));
  check_figure("Exp 2 read, WRENCH-cache", f[5], field("exp2_local", "wrench_cache_read_mean_error_pct"));
  check_figure("Exp 2 write", f[6], field("exp2_local", "write_mean_error_pct"));
  check_figure("Exp 2 write, WRENCH-cache", f[7], field("exp2_local", "wrench_cache_write_mean_error_pct"));
  check_figure("Exp 3 read", f[8], field("exp3_nfs", "read_mean_error_pct"));
  check_figure("Exp 3 read, WRENCH-cache", f[9], field("exp3_nfs", "wrench_cache_read_mean_error_pct"));
  check_figure("Exp 3 write", f[10], field("exp3_nfs", "write_mean_error_pct"));
  check_figure("Exp 3 write, WRENCH-cache", f[11], field("exp3_nfs", "wrench_cache_write_mean_error_pct"));
  check_figure("Exp 1 dirty memory", f[12],
               std::max(field("exp1_20gb", "max_dirty_diff_pct_of_memory"), field("exp1_100gb", "max_dirty_diff_pct_of_memory")));
  check_figure("Exp 1 cached memory", f[13],
               std::max(field("exp1_20gb", "max_cached_diff_pct_of_memory"), field("exp1_100gb", "max_cached_diff_pct_of_memory")));
}

TEST_CASE("the README's embedded default: its real run and pcsim's makespan", "[cli][docs]") {
  const auto f = figures(R"(\(its real run took ([0-9.]+) s; pcsim: ([0-9.]+) s\))");
  double real = 0.0;
  for (const auto& row : read_csv(validation_file("exp1_real_phase_times.csv"))) {
    if (row.at("file_size_gb") == "100") real = std::max(real, std::stod(row.at("end_s")));
  }
  check_figure("the real Exp 1 at 100 GB", f[0], real);
  const fs::path out = fresh("default");
  const std::string printed = run_pcsim({"run", "--out", out.string()});
  std::smatch m;
  REQUIRE(std::regex_search(printed, m, std::regex(R"(makespan ([0-9.]+) s)")));
  check_figure("pcsim run's makespan", f[1], std::stod(m[1].str()));
}

TEST_CASE("the README's WfCommons command: the instance's tasks, machine, cores, recorded makespan and pcsim's", "[cli][docs][inputs]") {
  const auto f = figures(R"(runs the ([0-9]+) tasks of an Epigenomics instance on the machine it was recorded on \(`compute-3`, ([0-9]+) cores\) )"
                         R"(with the `linux` profile: makespan ([0-9.]+) s\. The instance records ([0-9.]+) s)");
  const fs::path instance = fs::path(PCSIM_SOURCE_DIR) / "inputs" / "wfcommons" / "instances" / "epigenomics-chameleon-hep-1seq-100k-001.json";
  const std::string text = slurp(instance);
  std::size_t tasks = 0;
  for (std::size_t at = text.find("\"runtimeInSeconds\""); at != std::string::npos; at = text.find("\"runtimeInSeconds\"", at + 1)) ++tasks;
  check_figure("the instance's tasks", f[0], static_cast<double>(tasks));
  std::smatch m;
  REQUIRE(std::regex_search(text, m, std::regex(R"("nodeName": "compute-3"[^}]*"coreCount": ([0-9]+))")));
  check_figure("compute-3's cores", f[1], std::stod(m[1].str()));
  REQUIRE(std::regex_search(text, m, std::regex(R"("makespanInSeconds": ([0-9.]+))")));
  check_figure("the recorded makespan", f[3], std::stod(m[1].str()));
  // The README's command, from the repository's root, as a user runs it.
  const std::string command = fmt::format("cd '{}' && '{}' run {} --platform platforms/wfcommons-chameleon.xml --out '{}' 2>&1", PCSIM_SOURCE_DIR,
                                          PCSIM_BINARY, "inputs/wfcommons/instances/epigenomics-chameleon-hep-1seq-100k-001.json", fresh("epigenomics").string());
  REQUIRE(readme().find("build/bin/pcsim run inputs/wfcommons/instances/epigenomics-chameleon-hep-1seq-100k-001.json --platform "
                        "platforms/wfcommons-chameleon.xml") != std::string::npos);
  FILE* pipe = ::popen(command.c_str(), "r");
  REQUIRE(pipe != nullptr);
  std::string printed;
  char buffer[4096];
  while (std::size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) printed.append(buffer, n);
  REQUIRE(::pclose(pipe) == 0);
  REQUIRE(std::regex_search(printed, m, std::regex(R"(makespan ([0-9.]+) s)")));
  check_figure("pcsim run's makespan", f[2], std::stod(m[1].str()));
}

TEST_CASE("the README's paper-profile figures are pcsim's against WRENCH-cache's published outputs", "[cli][docs][paper]") {
  // Exp 1: every phase of the four sizes within the first figure, but the one named, whose
  // error is the second.
  const auto exp1 = figures(R"(every phase of the four file sizes is within ([0-9.]+) % of WRENCH-cache's published times but one )"
                            R"(\(75 GB, task 3 write: ([0-9.]+) %)");
  std::map<std::tuple<std::string, std::string, std::string>, double> wrench;
  for (const auto& row : read_csv(validation_file("exp1_wrench_cache_phase_times.csv"))) {
    wrench[{row.at("file_size_gb"), row.at("task"), row.at("phase")}] = std::stod(row.at("duration_s"));
  }
  double worst_other = 0.0, named = -1.0;
  const std::string scenario = (fs::path(PCSIM_SOURCE_DIR) / "scenarios/paper/exp1.toml").string();
  for (const auto& [size, cpu] : std::map<std::string, std::string>{{"20", "28"}, {"50", "75"}, {"75", "110"}, {"100", "155"}}) {
    const fs::path out = fresh("exp1-" + size);
    run_pcsim({"run", scenario, "--profile", "paper", "--set", "pipelines.file_size=\"" + size + " GB\"", "--set",
               "pipelines.cpu_time=\"" + cpu + " s\"", "--out", out.string(), "--quiet"});
    for (const auto& row : read_csv((out / "timeline.csv").string())) {
      const double want = wrench.at({size, row.at("task"), row.at("phase")});
      const double error = 100.0 * std::abs(duration(row) - want) / want;
      if (size == "75" && row.at("task") == "3" && row.at("phase") == "write") named = error;
      else worst_other = std::max(worst_other, error);
    }
  }
  INFO("worst other phase: " << worst_other << " %");
  CHECK(worst_other <= std::stod(exp1[0]));
  check_figure("Exp 1 75 GB task 3 write", exp1[1], named);

  // Exp 2: sorted per-task durations within the first figure up to the pipelines named; the
  // mean over n of the per-n error of the mean read and write times.
  const auto exp2 = figures(R"(per-task times agree within ([0-9.]+) % up to ([0-9]+) pipelines; beyond, the mean read and write times )"
                            R"(per pipeline differ from WRENCH-cache's by ([0-9.]+) % and ([0-9.]+) % on average over n)");
  std::map<std::pair<int, std::string>, std::vector<double>> theirs;
  for (const auto& row : read_csv(validation_file("exp2_wrench_cache_phase_times.csv"))) {
    theirs[{std::stoi(row.at("n_pipelines")), row.at("phase")}].push_back(std::stod(row.at("duration_s")));
  }
  const int agree_up_to = std::stoi(exp2[1]);
  double worst_task = 0.0;
  std::map<std::string, double> error_sum;
  for (int n = 1; n <= 32; ++n) {
    const fs::path out = fresh("exp2");
    run_pcsim({"run", (fs::path(PCSIM_SOURCE_DIR) / "scenarios/paper/exp2.toml").string(), "--profile", "paper", "--set",
               fmt::format("pipelines.count={}", n), "--out", out.string(), "--quiet", "--no-cache-contents"});
    std::map<std::string, std::vector<double>> ours;
    for (const auto& row : read_csv((out / "timeline.csv").string())) ours[row.at("phase")].push_back(duration(row));
    for (const std::string phase : {"read", "write"}) {
      std::vector<double> a = ours.at(phase), b = theirs.at({n, phase});
      REQUIRE(a.size() == b.size());
      std::sort(a.begin(), a.end());
      std::sort(b.begin(), b.end());
      if (n <= agree_up_to) {
        for (std::size_t i = 0; i < a.size(); ++i) worst_task = std::max(worst_task, 100.0 * std::abs(a[i] - b[i]) / b[i]);
      }
      double mean_a = 0.0, mean_b = 0.0;
      for (std::size_t i = 0; i < a.size(); ++i) {
        mean_a += a[i] / static_cast<double>(a.size());
        mean_b += b[i] / static_cast<double>(b.size());
      }
      error_sum[phase] += 100.0 * std::abs(mean_a - mean_b) / mean_b;
    }
    fs::remove_all(out);
  }
  INFO("worst task up to n = " << agree_up_to << ": " << worst_task << " %");
  CHECK(worst_task <= std::stod(exp2[0]));
  check_figure("Exp 2 mean read, paper profile vs WRENCH-cache", exp2[2], error_sum["read"] / 32);
  check_figure("Exp 2 mean write, paper profile vs WRENCH-cache", exp2[3], error_sum["write"] / 32);
}

TEST_CASE("the README's set-up commands build and run the pcsim the build makes, and name every package they install",
          "[cli][docs]") {
  const std::string raw = slurp(fs::path(PCSIM_SOURCE_DIR) / "README.md");
  // The first two fenced shell blocks: the run command, then the test command (.ci/run runs it).
  std::vector<std::string> commands;
  for (std::size_t at = raw.find("```sh\n"); at != std::string::npos && commands.size() < 2; at = raw.find("```sh\n", at + 1)) {
    const std::size_t begin = at + 6;
    commands.push_back(raw.substr(begin, raw.find('\n', begin) - begin));
  }
  REQUIRE(commands.size() == 2);
  // Command 1 builds the pcsim target alone and runs it where the build puts it.
  const fs::path binary = fs::path(PCSIM_BINARY);
  REQUIRE(binary.parent_path().filename() == "bin");
  CHECK_THAT(commands[0], Catch::Contains("--target pcsim && build/bin/pcsim run"));
  CHECK_THAT(commands[0], Catch::Contains("-DPAGECACHE_BUILD_TESTS=OFF"));
  // Command 2 turns the tests back on, whatever command 1 left in the build folder's cache.
  CHECK_THAT(commands[1], Catch::Contains("-DPAGECACHE_BUILD_TESTS=ON -DPAGECACHE_BUILD_BENCHMARKS=ON"));
  CHECK_THAT(commands[1], Catch::Contains("ctest --test-dir build"));
  // Every package scripts/install-deps can install is named in the README, in backquotes.
  const std::string script = slurp(fs::path(PCSIM_SOURCE_DIR) / "scripts" / "install-deps");
  std::size_t packages = 0;
  const std::regex list(R"((?:^|\n)[a-z_]+_packages=\(([^)]*)\))");
  for (auto it = std::sregex_iterator(script.begin(), script.end(), list); it != std::sregex_iterator(); ++it) {
    std::istringstream names((*it)[1].str());
    for (std::string name; names >> name;) {
      ++packages;
      INFO("scripts/install-deps installs " << name);
      CHECK_THAT(raw, Catch::Contains("`" + name + "`"));
    }
  }
  CHECK(packages >= 20);
}

TEST_CASE("the README's picture is of the report.html today's pcsim run writes", "[cli][docs]") {
  // scripts/report-picture draws docs/report-exp1.png and records the digests of the page it
  // drew and of the picture; a run whose page differs means the picture shows an older run.
  const fs::path docs = fs::path(PCSIM_SOURCE_DIR) / "docs";
  const std::string source = slurp(docs / "report-exp1.source");
  std::smatch page, picture;
  REQUIRE(std::regex_search(source, page, std::regex(R"(\nreport\.html sha256 ([0-9a-f]{64})\n)")));
  REQUIRE(std::regex_search(source, picture, std::regex(R"(\nreport-exp1\.png sha256 ([0-9a-f]{64})\n)")));
  const fs::path out = fresh("readme-picture");
  fs::create_directories(out);
  // The embedded default, run as the README's first command runs it.
  const auto run = run_child({PCSIM_BINARY, "run", "--quiet"}, 600.0, out.string());
  INFO(run.output);
  REQUIRE(run.status == 0);
  auto sha256 = [](const fs::path& file) {
    const auto r = run_child({"/usr/bin/sha256sum", file.string()}, 60.0);
    REQUIRE(r.status == 0);
    return r.output.substr(0, 64);
  };
  INFO("docs/report-exp1.png shows another run's page: scripts/report-picture draws it again");
  CHECK(sha256(out / "pcsim-out" / "report.html") == page[1].str());
  CHECK(sha256(docs / "report-exp1.png") == picture[1].str());
}

TEST_CASE("the README's training epochs: epoch times and shares from the page cache at 0.8x, 1.0x and 1.2x memory", "[cli][docs][file_sets]") {
  const auto f = figures(
      R"(With the data set at 0.8x memory \(8,000 files, as shipped\) epoch 1 takes ([0-9.]+) s from disk and epoch 2 ([0-9.]+) s, )"
      R"(([0-9.]+) % of it from the page cache; at 1.0x \(`--set file_sets.0.count=10000`\) epoch 2 takes ([0-9.]+) s, ([0-9.]+) % from )"
      R"(the cache; at 1.2x \(`--set file_sets.0.count=12000`\) ([0-9.]+) s, ([0-9.]+) % from the cache: .* Sequential epochs at 1.2x )"
      R"(\(`--set apps.0.tasks.0.access.0.pattern=sequential` too\) find ([0-9.]+) % in the cache, .* and epoch 2 takes ([0-9.]+) s, as epoch 1\.)");
  const std::string scenario = (fs::path(PCSIM_SOURCE_DIR) / "scenarios/examples/training-epochs.toml").string();
  // The epoch rows of a run with `sets`: [epoch] -> row.
  const auto epochs = [&](const std::string& name, const std::vector<std::string>& sets) {
    const fs::path out = fresh("training-" + name);
    std::vector<std::string> args{"run", scenario, "--out", out.string(), "--quiet"};
    for (const std::string& s : sets) args.insert(args.end(), {"--set", s});
    run_pcsim(args);
    std::map<int, pagecache::testing::CsvRow> rows;
    for (const auto& row : read_csv((out / "timeline.csv").string())) {
      std::smatch m;
      const std::string task = row.at("task");
      if (std::regex_match(task, m, std::regex(R"(train:images\[epoch ([0-9]+)\])"))) rows.emplace(std::stoi(m[1].str()), row);
    }
    REQUIRE(rows.size() == 3);
    return rows;
  };
  const auto cached_pct = [](const pagecache::testing::CsvRow& row) { return 100.0 * std::stod(row.at("cache_bytes")) / std::stod(row.at("bytes")); };
  const auto at_08 = epochs("0.8", {});
  check_figure("0.8x epoch 1", f[0], duration(at_08.at(1)));
  check_figure("0.8x epoch 2", f[1], duration(at_08.at(2)));
  check_figure("0.8x epoch 2 from cache", f[2], cached_pct(at_08.at(2)));
  const auto at_10 = epochs("1.0", {"file_sets.0.count=10000"});
  check_figure("1.0x epoch 2", f[3], duration(at_10.at(2)));
  check_figure("1.0x epoch 2 from cache", f[4], cached_pct(at_10.at(2)));
  const auto at_12 = epochs("1.2", {"file_sets.0.count=12000"});
  check_figure("1.2x epoch 2", f[5], duration(at_12.at(2)));
  check_figure("1.2x epoch 2 from cache", f[6], cached_pct(at_12.at(2)));
  const auto sequential = epochs("1.2-sequential", {"file_sets.0.count=12000", "apps.0.tasks.0.access.0.pattern=sequential"});
  check_figure("1.2x sequential epoch 2 from cache", f[7], cached_pct(sequential.at(2)));
  check_figure("1.2x sequential epoch 2", f[8], duration(sequential.at(2)));
  // The physics, whatever the README says: a data set that fits is read from memory from epoch
  // 2 on; one that does not is read in order from disk every epoch.
  CHECK(at_08.at(2).at("disk_bytes") == "0");
  CHECK(sequential.at(2).at("cache_bytes") == "0");
  CHECK(duration(sequential.at(2)) == Approx(duration(sequential.at(1))));
}

namespace {

// The epoch rows of `scenario` (scenarios/examples/) run with `sets`, task `task`: [epoch] -> row.
std::map<int, pagecache::testing::CsvRow> access_epochs(const std::string& scenario, const std::string& task, const std::string& name,
                                                        const std::vector<std::string>& sets) {
  const fs::path out = fresh(name);
  std::vector<std::string> args{"run", (fs::path(PCSIM_SOURCE_DIR) / "scenarios/examples" / scenario).string(), "--out", out.string(), "--quiet"};
  for (const std::string& s : sets) args.insert(args.end(), {"--set", s});
  run_pcsim(args);
  std::map<int, pagecache::testing::CsvRow> rows;
  for (const auto& row : read_csv((out / "timeline.csv").string())) {
    std::smatch m;
    const std::string label = row.at("task");
    if (std::regex_match(label, m, std::regex(task + R"(\[epoch ([0-9]+)\])"))) rows.emplace(std::stoi(m[1].str()), row);
  }
  REQUIRE(rows.size() == 2);
  return rows;
}

double cached_share(const pagecache::testing::CsvRow& row) { return std::stod(row.at("cache_bytes")) / std::stod(row.at("bytes")); }

}  // namespace

TEST_CASE("the README's hyperslab reads: epoch 2 from memory when the block fits, from disk when it does not", "[cli][docs][access]") {
  const auto f = figures(R"(Epoch 1 takes ([0-9.]+) s from disk, each request a disk request \(strided requests are not read ahead\), and )"
                         R"(epoch 2 ([0-9.]+) s, ([0-9.]+) % from the page cache, .* no longer fits: epoch 2 finds ([0-9.]+) % in the cache )"
                         R"(and takes ([0-9.]+) s, as epoch 1\.)");
  const auto fits = access_epochs("hyperslab-reads.toml", "slab:array", "hyperslab", {});
  check_figure("epoch 1", f[0], duration(fits.at(1)));
  check_figure("epoch 2", f[1], duration(fits.at(2)));
  check_figure("epoch 2 from cache", f[2], 100.0 * cached_share(fits.at(2)));
  const auto wide = access_epochs("hyperslab-reads.toml", "slab:array", "hyperslab-wide", {"apps.0.tasks.0.access.0.request=\"200 kB\""});
  check_figure("wide epoch 2 from cache", f[3], 100.0 * cached_share(wide.at(2)));
  check_figure("wide epoch 2", f[4], duration(wide.at(2)));
  // The physics: epoch 1 misses everything, each request a disk request of its pages (80 us
  // and its whole pages at 2 GB/s: 50 kB rows of 500 kB from 100 kB on, 13 or 14 pages each);
  // a block that fits is read from memory in epoch 2.
  CHECK(fits.at(1).at("cache_bytes") == "0");
  CHECK(fits.at(1).at("disk_bytes") == fits.at(1).at("bytes"));
  double pages = 0.0;
  for (std::int64_t row = 0; row < 100'000; ++row) {
    const std::int64_t first = 100'000 + row * 500'000, end = first + 50'000;
    pages += static_cast<double>((end + 4095) / 4096 - first / 4096);
  }
  CHECK(duration(fits.at(1)) == Approx(100'000 * 80e-6 + pages * 4096 / 2e9).epsilon(0.001));
  CHECK(fits.at(2).at("disk_bytes") == "0");
  CHECK(duration(wide.at(2)) == Approx(duration(wide.at(1))));
}

TEST_CASE("the README's key-value reads: the share from the cache is the share of the file it holds", "[cli][docs][access]") {
  const auto f = figures(R"(in epoch 2 ([0-9.]+) % of the bytes come from the page cache, as the share of the file it holds \(256 MB of 1 GB, )"
                         R"(([0-9.]+) %\), and a read takes ([0-9.]+) us on average\. With `advice = "random"`)");
  const auto normal = access_epochs("key-value-random.toml", "get:db", "key-value", {});
  check_figure("epoch 2 from cache", f[0], 100.0 * cached_share(normal.at(2)));
  check_figure("memory over file", f[1], 100.0 * 256e6 / 1e9);
  check_figure("time per read", f[2], duration(normal.at(2)) / 500'000 * 1e6);
  // The physics: the hit share is the cache's share of the file, within a point.
  CHECK(cached_share(normal.at(2)) == Approx(0.256).margin(0.01));
  // POSIX_FADV_RANDOM changes nothing: random requests are not read ahead under normal advice.
  const auto random = access_epochs("key-value-random.toml", "get:db", "key-value-fadv", {"apps.0.tasks.0.access.0.advice=random"});
  for (const int e : {1, 2}) {
    CHECK(random.at(e).at("end_s") == normal.at(e).at("end_s"));
    CHECK(random.at(e).at("cache_bytes") == normal.at(e).at("cache_bytes"));
  }
}

TEST_CASE("the README's fio jobs: a file read after fio's invalidate comes from the disk, with invalidate=0 from memory", "[cli][docs][fio]") {
  const auto f = figures(R"(read back at ([0-9.]+) MB/s after fio's `invalidate=1` dropped it from the cache, read again at ([0-9.]+) MB/s )"
                         R"(with `invalidate=0`, then four jobs of random 4 KiB reads of its first 256 MiB, the first at ([0-9.]+) IOPS)");
  const fs::path out = fresh("fio-jobs");
  run_pcsim({"run", (fs::path(PCSIM_SOURCE_DIR) / "scenarios/examples/fio-jobs.toml").string(), "--out", out.string(), "--quiet"});
  const std::string fio = slurp(out / "fio.json");
  // The jobs' lines of fio.json, in order: write, read-cold, read-warm, random and its clones.
  std::vector<std::string> jobs;
  for (std::size_t at = fio.find("{\"jobname\""); at != std::string::npos; at = fio.find("{\"jobname\"", at + 1)) {
    jobs.push_back(fio.substr(at, fio.find("\"job_runtime\"", at) - at));
  }
  REQUIRE(jobs.size() == 7);
  const auto field = [](const std::string& job, const std::string& direction, const std::string& key) {
    const std::string part = job.substr(job.find("\"" + direction + "\": {"));
    const std::size_t at = part.find("\"" + key + "\": ") + key.size() + 4;
    return std::stod(part.substr(at, part.find_first_of(",}", at) - at));
  };
  check_figure("read-cold MB/s", f[0], field(jobs[1], "read", "bw_bytes") / 1e6);
  check_figure("read-warm MB/s", f[1], field(jobs[2], "read", "bw_bytes") / 1e6);
  check_figure("random IOPS", f[2], field(jobs[3], "read", "iops"));
  // The physics: the cold read from the disk, the warm one from memory, each 2 GiB.
  const auto rows = read_csv((out / "timeline.csv").string());
  for (const auto& row : rows) {
    if (row.at("app") == "read-cold" && row.at("bytes") != "0") CHECK(row.at("disk_bytes") == std::to_string(std::int64_t{2} << 30));
    if (row.at("app") == "read-warm" && row.at("bytes") != "0") CHECK(row.at("cache_bytes") == std::to_string(std::int64_t{2} << 30));
  }
}
