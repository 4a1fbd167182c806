// pcsim: the command line. Thin: parse, build, run, report.
//
// Until the page cache model and scenario files land, `pcsim run` runs one embedded scenario
// on the device layer alone: concurrent pipelines that read a file from a shared disk,
// compute on shared cores and write a file back, every transfer timed by the fair-share
// model. It prints a table per pipeline and writes timeline.csv into --out.

#include <pagecache/devices.hpp>
#include <pagecache/error.hpp>
#include <pagecache/simulator.hpp>
#include <pagecache/version.hpp>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using namespace pagecache;

struct PhaseRecord {
  int app;
  std::string phase;
  double start;
  double end;
  std::int64_t bytes;
};

struct Platform {
  explicit Platform(Simulator& sim)
      : share(sim), disk(share, "disk", 465e6, 465e6), cpu(share, "cpu", 32) {}
  FairShare share;
  Disk disk;
  Cpu cpu;
};

Task<void> pipeline(Simulator& sim, const Platform& platform, int app, std::int64_t file_bytes,
                    double cpu_seconds, std::vector<PhaseRecord>& records) {
  double start = sim.now();
  co_await platform.disk.read(file_bytes);
  records.push_back({app, "read", start, sim.now(), file_bytes});
  start = sim.now();
  co_await platform.cpu.compute(cpu_seconds);
  records.push_back({app, "compute", start, sim.now(), 0});
  start = sim.now();
  co_await platform.disk.write(file_bytes);
  records.push_back({app, "write", start, sim.now(), file_bytes});
}

void write_timeline(const fs::path& path, const std::vector<PhaseRecord>& records) {
  std::ofstream out(path);
  out << "app,task,phase,start_s,end_s,bytes\n";
  for (const auto& r : records) out << fmt::format("{},1,{},{:.6f},{:.6f},{}\n", r.app, r.phase, r.start, r.end, r.bytes);
  if (!out) throw Error(fmt::format("cannot write {}", path.string()));
}

// Writes into a temporary sibling folder, then renames it over `out`: a failed run never
// leaves a half-written result behind.
void publish(const fs::path& out, const std::vector<PhaseRecord>& records) {
  const fs::path staging = out.string() + ".tmp";
  fs::remove_all(staging);
  fs::create_directories(staging);
  write_timeline(staging / "timeline.csv", records);
  fs::remove_all(out);
  fs::rename(staging, out);
}

int run(const std::string& out_dir, int pipelines, bool quiet) {
  const auto wall_start = std::chrono::steady_clock::now();
  Simulator sim;
  Platform platform(sim);
  std::vector<PhaseRecord> records;
  constexpr std::int64_t kFileBytes = 3'000'000'000;
  constexpr double kCpuSeconds = 4.4;
  for (int app = 1; app <= pipelines; ++app) sim.spawn(pipeline(sim, platform, app, kFileBytes, kCpuSeconds, records));
  sim.run();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();

  publish(out_dir, records);
  if (!quiet) {
    fmt::print("pcsim {}: {} pipelines, each reads 3 GB, computes 4.4 s, writes 3 GB\n", kVersion, pipelines);
    fmt::print("platform: disk 465 MB/s shared by all transfers, 32 cores (no page cache yet)\n\n");
    fmt::print("{:>4} {:>8} {:>10} {:>10} {:>10}\n", "app", "phase", "start_s", "end_s", "MB/s");
    for (const auto& r : records) {
      const double rate = r.bytes > 0 ? static_cast<double>(r.bytes) / (r.end - r.start) / 1e6 : 0.0;
      fmt::print("{:>4} {:>8} {:>10.2f} {:>10.2f} {:>10.1f}\n", r.app, r.phase, r.start, r.end, rate);
    }
    fmt::print("\nmakespan {:.2f} s; {} events in {:.3f} s wall; outputs in {}/\n", sim.now(),
               sim.events_processed(), wall, out_dir);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"pcsim: a discrete-event simulator of the Linux page cache"};
  app.set_version_flag("--version", std::string("pcsim ") + pagecache::kVersion);
  app.require_subcommand(1);
  auto* run_cmd = app.add_subcommand("run", "run the embedded default scenario");
  std::string out_dir = "pcsim-out";
  int pipelines = 4;
  bool quiet = false;
  run_cmd->add_option("--out", out_dir, "output folder")->capture_default_str();
  run_cmd->add_option("--pipelines", pipelines, "number of concurrent pipelines")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  run_cmd->add_flag("--quiet", quiet, "print nothing");
  CLI11_PARSE(app, argc, argv);
  try {
    return run(out_dir, pipelines, quiet);
  } catch (const pagecache::ConfigError& e) {
    fmt::print(stderr, "pcsim: {}\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    fmt::print(stderr, "pcsim: {}\n", e.what());
    return 1;
  }
}
