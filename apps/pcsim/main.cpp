// pcsim: the command line. Thin: parse, build, run, report.
//
// Until scenario files land, `pcsim run` runs one embedded scenario: the paper's Exp 1 (one
// pipeline of three tasks, each reading a file, computing and writing the next file) on the
// paper's host with the `paper` profile. It prints a table of phases and writes
// timeline.csv into --out.

#include <pagecache/error.hpp>
#include <pagecache/host.hpp>
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
  int task;
  std::string phase;
  double start;
  double end;
  std::int64_t bytes;
  std::int64_t cache_bytes;
  std::int64_t disk_bytes;
};

Task<void> pipeline(Simulator& sim, Host& host, int app, std::vector<FileRef> files, double cpu_seconds,
                    std::vector<PhaseRecord>& records) {
  constexpr std::int64_t kChunk = 100'000'000;
  for (int task = 1; task <= 3; ++task) {
    const IoResult read = co_await host.read_file(files[static_cast<std::size_t>(task - 1)], kChunk);
    records.push_back({app, task, "read", read.start, read.end, read.bytes, read.cache_bytes, read.disk_bytes});
    const double start = sim.now();
    co_await host.compute(cpu_seconds);
    records.push_back({app, task, "compute", start, sim.now(), 0, 0, 0});
    const IoResult write = co_await host.write_file(files[static_cast<std::size_t>(task)], kChunk);
    records.push_back({app, task, "write", write.start, write.end, write.bytes, write.cache_bytes, write.disk_bytes});
    host.release_memory(read.bytes);
  }
}

void write_timeline(const fs::path& path, const std::vector<PhaseRecord>& records) {
  std::ofstream out(path);
  out << "app,task,phase,start_s,end_s,bytes,cache_bytes,disk_bytes\n";
  for (const auto& r : records) {
    out << fmt::format("{},{},{},{:.6f},{:.6f},{},{},{}\n", r.app, r.task, r.phase, r.start, r.end, r.bytes,
                       r.cache_bytes, r.disk_bytes);
  }
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

int run(const std::string& out_dir, std::int64_t size_gb, bool quiet) {
  const auto wall_start = std::chrono::steady_clock::now();
  Simulator sim;
  FairShare share(sim);
  Host host(sim, share,
            HostSpec{.name = "node",
                     .cores = 32,
                     .memory = 268'000'000'000,
                     .memory_bandwidth = MemoryBandwidth::shared_channel(4812e6),
                     .cache = CacheSettings::paper()});
  const DiskRef disk = host.add_disk("ssd", 465e6, 465e6);
  std::vector<FileRef> files;
  for (int i = 1; i <= 4; ++i) files.push_back(host.add_file(fmt::format("file_{}", i), size_gb * 1'000'000'000, disk));
  // The paper's measured CPU time per task grows with the file size (Table: 28 s for 20 GB
  // ... 155 s for 100 GB): about 1.55 s per GB.
  const double cpu_seconds = 1.55 * static_cast<double>(size_gb);
  std::vector<PhaseRecord> records;
  sim.spawn(pipeline(sim, host, 1, files, cpu_seconds, records));
  sim.run();
  const double makespan = records.back().end;
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();

  publish(out_dir, records);
  if (!quiet) {
    fmt::print("pcsim {}: the paper's Exp 1 (profile paper): 3 tasks, each reads {} GB, computes {:.0f} s, "
               "writes {} GB\n",
               kVersion, size_gb, cpu_seconds, size_gb);
    fmt::print("host: 268 GB memory (4812 MB/s), disk 465 MB/s, dirty_ratio 0.4, 5 s flusher, 30 s expiry\n\n");
    fmt::print("{:>4} {:>8} {:>9} {:>9} {:>9} {:>9} {:>9}\n", "task", "phase", "start_s", "end_s", "MB/s", "cache_GB", "disk_GB");
    for (const auto& r : records) {
      const double rate = r.bytes > 0 ? static_cast<double>(r.bytes) / (r.end - r.start) / 1e6 : 0.0;
      fmt::print("{:>4} {:>8} {:>9.2f} {:>9.2f} {:>9.1f} {:>9.1f} {:>9.1f}\n", r.task, r.phase, r.start, r.end, rate,
                 static_cast<double>(r.cache_bytes) / 1e9, static_cast<double>(r.disk_bytes) / 1e9);
    }
    fmt::print("\nmakespan {:.2f} s; written back: {:.1f} GB forced, {:.1f} GB by the flusher; evicted {:.1f} GB\n",
               makespan, static_cast<double>(host.forced_flush_bytes()) / 1e9,
               static_cast<double>(host.periodic_flush_bytes()) / 1e9, static_cast<double>(host.evicted_bytes()) / 1e9);
    fmt::print("{} events in {:.3f} s wall; outputs in {}/\n", sim.events_processed(), wall, out_dir);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"pcsim: a discrete-event simulator of the Linux page cache"};
  app.set_version_flag("--version", std::string("pcsim ") + pagecache::kVersion);
  app.require_subcommand(1);
  auto* run_cmd = app.add_subcommand("run", "run the embedded default scenario (the paper's Exp 1)");
  std::string out_dir = "pcsim-out";
  std::int64_t size_gb = 100;
  bool quiet = false;
  run_cmd->add_option("--out", out_dir, "output folder")->capture_default_str();
  run_cmd->add_option("--size-gb", size_gb, "file size in GB")->check(CLI::Range(1, 250))->capture_default_str();
  run_cmd->add_flag("--quiet", quiet, "print nothing");
  CLI11_PARSE(app, argc, argv);
  try {
    return run(out_dir, size_gb, quiet);
  } catch (const pagecache::ConfigError& e) {
    fmt::print(stderr, "pcsim: {}\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    fmt::print(stderr, "pcsim: {}\n", e.what());
    return 1;
  }
}
