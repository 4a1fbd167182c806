// The cost of one run through the C++ API, as pcsim.run makes it (benchmarks/python/): load the
// scenario, attach report.html's recorder, run; REPS times in one process, each timed, and the
// median printed in seconds. Beside it, benchmarks/python/run_call.py times pcsim.run the same
// way; benchmarks/python/overhead.sh alternates the two.
//   api_run SCENARIO REPS [KEY=VALUE ...]

#include <pagecache/outputs.hpp>
#include <pagecache/run.hpp>
#include <pagecache/scenario_file.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: api_run SCENARIO REPS [KEY=VALUE ...]\n");
    return 2;
  }
  std::vector<std::pair<std::string, std::string>> overrides;
  for (int i = 3; i < argc; ++i) {
    const std::string set = argv[i];
    overrides.emplace_back(set.substr(0, set.find('=')), set.substr(set.find('=') + 1));
  }
  const int reps = std::atoi(argv[2]);
  std::vector<double> seconds;
  for (int r = 0; r < reps; ++r) {
    const auto start = std::chrono::steady_clock::now();
    pagecache::Scenario scenario = pagecache::load_scenario(argv[1], overrides);
    pagecache::RunOutputs outputs({.report = true, .trace = false});
    pagecache::RunOptions options;
    outputs.attach(options);
    const pagecache::RunResult result = pagecache::run_scenario(std::move(scenario), options);
    seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    if (result.timeline.empty()) return 1;
  }
  std::nth_element(seconds.begin(), seconds.begin() + static_cast<std::ptrdiff_t>(seconds.size() / 2), seconds.end());
  std::printf("%.9f\n", seconds[seconds.size() / 2]);
  return 0;
}
