// A program of someone else's, built against an installed (or built) pagecache with its public
// headers only. Without arguments: four 100 MB reads share a 100 MB/s disk (done at 4 s).
// With SCENARIO OUT: runs the scenario file and writes the outputs `pcsim run` writes, through
// the library's own writers, for the test to compare with pcsim's.
#include <pagecache/devices.hpp>
#include <pagecache/error.hpp>
#include <pagecache/outputs.hpp>
#include <pagecache/run.hpp>
#include <pagecache/scenario_file.hpp>
#include <pagecache/simulator.hpp>

#include <cstdio>
#include <string>

namespace {
pagecache::Task<void> reader(const pagecache::Disk& disk) { co_await disk.read(100'000'000); }

int four_readers() {
  pagecache::Simulator sim;
  pagecache::FairShare share(sim);
  pagecache::Disk disk(share, "disk", 100e6, 100e6);
  for (int i = 0; i < 4; ++i) sim.spawn(reader(disk));
  sim.run();
  std::printf("done at %g s\n", sim.now());
  return sim.now() == 4.0 ? 0 : 1;
}

int run(const std::string& scenario_file, const std::string& out) {
  const pagecache::Scenario scenario = pagecache::load_scenario(scenario_file);
  pagecache::check_output_folder(out, scenario_file);
  pagecache::RunOutputs outputs({.report = true, .trace = scenario.trace});
  pagecache::RunOptions options;
  outputs.attach(options);
  const pagecache::RunResult result = pagecache::run_scenario(scenario, options);
  for (const std::string& warning : outputs.write(out, scenario, result)) std::fprintf(stderr, "warning: %s\n", warning.c_str());
  std::printf("%s", pagecache::readable_summary(scenario, result).c_str());
  return 0;
}
}  // namespace

int main(int argc, char** argv) {
  if (argc == 1) return four_readers();
  if (argc != 3) {
    std::fprintf(stderr, "usage: consumer [SCENARIO OUT]\n");
    return 2;
  }
  try {
    return run(argv[1], argv[2]);
  } catch (const pagecache::Error& e) {
    std::fprintf(stderr, "consumer: %s\n", e.what());
    return 1;
  }
}
