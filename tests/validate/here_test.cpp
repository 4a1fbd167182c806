// validate --here without running any I/O: the measurements' files read back as written,
// their errors naming file and line, the cases sized against memory, and the scoring's metric
// on measurements whose phases are known.
#include "validate/here.hpp"

#include <pagecache/error.hpp>
#include <pagecache/run.hpp>
#include <pagecache/scenario_file.hpp>

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>

using namespace pagecache;
using namespace pagecache::validate;
using calibrate::RealCase;
using calibrate::RealPhase;
using calibrate::RealRun;

namespace {

const char* kPlatform = R"(
[[hosts]]
name = "m"
cores = 4
memory = "16 GB"
memory_read_bw = "4 GB/s"
memory_write_bw = "2 GB/s"
[hosts.page_cache]
dirty_ratio = 0.2
dirty_background_ratio = 0.1
[[hosts.disks]]
name = "disk"
read_bw = "500 MB/s"
write_bw = "250 MB/s"
)";

std::filesystem::path scratch(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("pcsim-here-test-" + std::to_string(::getpid()) + "-" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// A case's "real" run whose phases are pcsim's own on kPlatform, `stretch` times longer.
RealRun run_like_pcsim(const RealCase& spec, int repetition, double stretch) {
  const Scenario s = parse_scenario(fmt::format("{}\n[pipelines]\ncount = {}\nfile_size = \"{} B\"\ntasks = {}\ncpu_time = \"{} s\"\nchunk_size = \"{} B\"\n",
                                                kPlatform, spec.pipelines, spec.file_size, spec.tasks, spec.compute, spec.chunk),
                                    "<test>");
  const RunResult r = run_scenario(s);
  RealRun run;
  run.spec = spec;
  run.repetition = repetition;
  run.memory_total = 16'000'000'000;
  run.dropped_all_caches = true;
  for (const PhaseRow& row : r.timeline) {
    run.phases.push_back(RealPhase{std::stoi(r.app_name(row)), std::stoi(r.task_name(row)), std::string(to_string(row.phase)), row.start * stretch,
                                     row.end * stretch});
    run.makespan = std::max(run.makespan, row.end * stretch);
  }
  run.memory.push_back({0.0, 16'000'000'000, 0, 0, 0});
  return run;
}

}  // namespace

TEST_CASE("validate --here sizes its cases against the memory available", "[validate][here]") {
  const auto cases = here_cases(20'000'000'000, false);
  REQUIRE(cases.size() == 5);
  CHECK(cases[0].file_size == 1'600'000'000);  // 8 % of 20 GB, whole 100 MB chunks
  CHECK(cases[1].file_size == 4'000'000'000);
  CHECK(cases[2].file_size == 8'000'000'000);
  CHECK(cases[3].pipelines == 4);
  CHECK(cases[4].pipelines == 8);
  CHECK(cases[3].file_size == 200'000'000);  // 1.2 % is 240 MB: two chunks
  CHECK(here_files(HereMeasurements{}).size() == 4);
  CHECK(here_cases(1'000'000, false)[0].file_size == 100'000'000);  // at least a chunk
}

TEST_CASE("validate --here scores the paper's metric: no error against itself, 1 - 1 / 1.1 for phases 10 % longer", "[validate][here]") {
  const RealCase spec{"c", 2, 2, 300'000'000, 0.5, 100'000'000};
  HereMeasurements m;
  m.platform_toml = kPlatform;
  m.runs.push_back(run_like_pcsim(spec, 1, 1.0));
  m.runs.push_back(run_like_pcsim(spec, 2, 1.0));
  const std::string same = score_here(m);
  INFO(same);
  CHECK_THAT(same, Catch::Contains("c: 2 pipelines of 2 tasks, files of 300 MB, 2 repetitions: makespan error 0.0 %") &&
                       Catch::Contains("mean phase error 0.0 %"));
  // One repetition 20 % longer: the mean is 10 % longer, the spread 20 / 1.1 = 18.2 %.
  m.runs[1] = run_like_pcsim(spec, 2, 1.2);
  const std::string longer = score_here(m);
  INFO(longer);
  CHECK_THAT(longer, Catch::Contains("makespan error 9.1 %") && Catch::Contains("spread 18.2 %") && Catch::Contains("mean phase error 9.1 %"));
}

TEST_CASE("validate --here measurements are read back as written, and a bad file is named with its line", "[validate][here]") {
  const RealCase spec{"c", 1, 1, 100'000'000, 0.25, 50'000'000};
  HereMeasurements m;
  m.platform_toml = kPlatform;
  m.runs.push_back(run_like_pcsim(spec, 1, 1.5));
  m.runs.back().memory.push_back({0.5, 15'000'000'000, 100'000'000, 50'000'000, 1'000'000});
  const auto dir = scratch("roundtrip");
  for (const auto& [name, text] : here_files(m)) std::ofstream(dir / name) << text;
  const HereMeasurements back = load_here(dir);
  REQUIRE(back.runs.size() == 1);
  CHECK(back.platform_toml == m.platform_toml);
  CHECK(back.runs[0].spec.name == "c");
  CHECK(back.runs[0].spec.file_size == 100'000'000);
  CHECK(back.runs[0].phases.size() == m.runs[0].phases.size());
  CHECK(back.runs[0].memory.size() == 2);
  CHECK(back.runs[0].memory[1].dirty == 50'000'000);
  CHECK(score_here(back) == score_here(m));
  CHECK(back.runs[0].others_busy_cores == -1.0);  // not recorded
  CHECK(back.runs[0].reported == -1);

  // The machine's activity during a run, kept and said; the calibration's notes repeated.
  m.runs[0].others_busy_cores = 0.75;
  m.runs[0].steal_pct = 6.5;
  m.runs[0].reported = 3'000'000'000;
  m.runs[0].warm_at_start = 0;  // waited until the kernel had reported what was freed
  m.platform_toml = std::string("# Note: a virtual machine\n") + kPlatform;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  for (const auto& [name, text] : here_files(m)) std::ofstream(dir / name) << text;
  const HereMeasurements busy = load_here(dir);
  CHECK(busy.runs[0].others_busy_cores == 0.75);
  CHECK(busy.runs[0].steal_pct == 6.5);
  CHECK(busy.runs[0].reported == 3'000'000'000);
  const std::string said = score_here(busy);
  INFO(said);
  CHECK_THAT(said, Catch::Contains("other work kept up to 0.75 cores busy during a run (c repetition 1)") &&
                       Catch::Contains("took up to 6.5 % of the CPUs' time") && Catch::Contains("3.0 GB of free memory went back") &&
                       Catch::Contains("calibration note: a virtual machine"));
  // A folder from before the warm memory at the start was recorded (15 fields), and one from
  // before the activity was (12 fields), are still read.
  const auto cut_columns = [&](int columns) {
    std::string runs;
    std::ifstream in(dir / "runs.csv");
    for (std::string line; std::getline(in, line);) {
      for (int cut = 0; cut < columns; ++cut) line = line.substr(0, line.rfind(','));
      runs += line + "\n";
    }
    in.close();
    std::ofstream(dir / "runs.csv") << runs;
  };
  CHECK(load_here(dir).runs[0].warm_at_start == m.runs[0].warm_at_start);
  cut_columns(1);
  CHECK(load_here(dir).runs[0].warm_at_start == -1);
  CHECK(load_here(dir).runs[0].others_busy_cores != -1.0);
  cut_columns(3);
  CHECK(load_here(dir).runs[0].others_busy_cores == -1.0);

  std::ofstream(dir / "phases.csv", std::ios::app) << "c,1,1,1,read,zero,1.0\n";
  CHECK_THROWS_WITH(load_here(dir), Catch::Contains("phases.csv:5: column 'start_s': 'zero' is not a number"));
  std::ofstream(dir / "phases.csv") << "case,repetition,pipeline,task,phase,start_s,end_s\nd,1,1,1,read,0,1\n";
  CHECK_THROWS_WITH(load_here(dir), Catch::Contains("phases.csv:2: case d repetition 1 is not in runs.csv"));
  const std::string runs_csv = here_files(m)[1].second;
  std::ofstream(dir / "runs.csv") << runs_csv.substr(0, runs_csv.find('\n') + 1) << "c,1\n";  // its header, and a short row
  CHECK_THROWS_WITH(load_here(dir), Catch::Contains("runs.csv:2: 2 fields, expected 16"));
  std::filesystem::remove(dir / "platform.toml");
  CHECK_THROWS_AS(load_here(dir), ConfigError);
  std::filesystem::remove_all(dir);
}
