// The `paper` profile reproduces WRENCH-cache's published Exp 1 (one pipeline, 20/50/75/100
// GB files, local disk): every phase time, and the per-file cache contents after every I/O
// phase. Expected values are WRENCH-cache's outputs from the paper's repository
// (validation/paper/, see its README), not pcsim's.
#include "support/csv.hpp"
#include "support/paper_pipeline.hpp"

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <cmath>
#include <map>
#include <tuple>

using namespace pagecache;
using namespace pagecache::testing;

namespace {

struct Exp1Run {
  std::vector<PhaseRecord> phases;
  std::vector<CacheRecord> cache;
};

Exp1Run run_exp1(int size_gb, double cpu_seconds) {
  Simulator sim;
  FairShare share(sim);
  Host host(sim, share, wrench_cache_host());
  host.set_checking(true);
  const DiskRef disk = host.add_disk("disk", 465e6, 465e6);
  std::vector<FileRef> files;
  for (int i = 1; i <= 4; ++i) {
    files.push_back(host.add_file(fmt::format("file_{}", i), static_cast<std::int64_t>(size_gb) * 1'000'000'000, disk));
  }
  Exp1Run run;
  sim.spawn(paper_pipeline(sim, host, files, cpu_seconds, 100'000'000, 1, run.phases, &run.cache));
  sim.run();
  host.check_invariants();
  return run;
}

const Exp1Run& exp1(int size_gb) {
  static const std::map<int, Exp1Run> runs = [] {
    std::map<int, Exp1Run> all;
    for (const auto& [size, seconds] : std::map<int, double>{{20, 28.0}, {50, 75.0}, {75, 110.0}, {100, 155.0}}) {
      all[size] = run_exp1(size, seconds);
    }
    return all;
  }();
  return runs.at(size_gb);
}

// The one phase outside 1 % (pcsim is 1.5 % faster). WRENCH-cache's own memory profile
// shows why: its flusher ticks at 627.86 s and 632.86 s (cutoffs 597.86 s and 602.86 s) and
// leaves 420 MB dirty although nothing has been written since 509.4 s, so that data is
// invisible to its flusher; task 3's write then starts with 420 MB more dirty data than in
// pcsim, whose flusher wrote everything, and reaches the dirty limit sooner.
double tolerance(int size_gb, int task, const std::string& phase) {
  return size_gb == 75 && task == 3 && phase == "write" ? 0.02 : 0.01;
}

}  // namespace

TEST_CASE("paper profile: Exp 1 phase times match WRENCH-cache's", "[paper][exp1]") {
  std::map<std::tuple<int, int, std::string>, double> expected;
  for (const auto& row : read_csv(validation_file("exp1_wrench_cache_phase_times.csv"))) {
    expected[{std::stoi(row.at("file_size_gb")), std::stoi(row.at("task")), row.at("phase")}] = std::stod(row.at("duration_s"));
  }
  for (int size : {20, 50, 75, 100}) {
    const Exp1Run& run = exp1(size);
    REQUIRE(run.phases.size() == 9);
    for (const PhaseRecord& p : run.phases) {
      const double want = expected.at({size, p.task, p.phase});
      INFO(size << " GB, task " << p.task << " " << p.phase << ": pcsim " << p.duration() << " s, WRENCH-cache " << want << " s");
      CHECK(std::abs(p.duration() - want) / want <= tolerance(size, p.task, p.phase));
    }
  }
}

TEST_CASE("paper profile: Exp 1 cache contents match WRENCH-cache's within 0.5 GB per file", "[paper][exp1]") {
  std::map<std::tuple<int, int, std::string, int>, double> expected;
  for (const auto& row : read_csv(validation_file("exp1_wrench_cache_cache_contents.csv"))) {
    const int file = std::stoi(row.at("file").substr(5));  // file_N
    expected[{std::stoi(row.at("file_size_gb")), std::stoi(row.at("after_task")), row.at("after_phase"), file}] =
        std::stod(row.at("cached_gb"));
  }
  for (int size : {20, 50, 75, 100}) {
    const Exp1Run& run = exp1(size);
    REQUIRE(run.cache.size() == 24);
    for (const CacheRecord& c : run.cache) {
      const double want = expected.at({size, c.task, c.phase, c.file});
      const double got = static_cast<double>(c.cached) / 1e9;
      INFO(size << " GB, after task " << c.task << " " << c.phase << ", file_" << c.file << ": pcsim " << got
                << " GB, WRENCH-cache " << want << " GB");
      CHECK(std::abs(got - want) <= 0.5);
    }
  }
}
