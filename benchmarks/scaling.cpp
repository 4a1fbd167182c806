// pcsim_scaling: how pcsim's cost grows with the number of concurrent applications.
//
// This times the simulation alone, its scenario built in memory. The user's command, `pcsim
// run SCENARIO --out DIR` with the TOML read and every output and the report written, is
// measured by scripts/bench-user (Exp 2 scaled, many writers, this cluster, a DAG).
//
// N pipelines of 3 tasks (read a file, compute, write the next file) in 100 MB chunks run on
// one host scaled to them: per pipeline one core, 2.5 GB of memory, 500 MB/s of disk, so
// that every pipeline sees the same machine whatever N. Its files (1 GB each, four per
// pipeline, read and written once) do not all fit in the page cache beside the buffers: the
// run evicts, writes back under the dirty limits and reads from disk and cache. For each N it
// reports the simulated makespan, events processed, chunk operations, wall time of the
// simulation (the run, not the set-up), chunk operations per second, nanoseconds per chunk
// operation and the peak resident set size of the process (getrusage), as a table and as one
// JSON line per N.
//
// The machine is shared: another tenant can slow a run by half. Each N is repeated until a
// time budget is spent (1 s by default, at most 1000 repetitions, at least one): the figures
// are those of the fastest repetition, the one least disturbed, and the median is printed
// beside them to show the spread.
//
//   pcsim_scaling                       # N = 10, 100, 1000, 10^4, 10^5, each in a fresh process
//   pcsim_scaling --max 1000            # stop at N = 1000
//   pcsim_scaling --pipelines 5000      # one N, in this process: its JSON line only
//   pcsim_scaling --budget 0            # one repetition per N
//   pcsim_scaling --profile paper       # the paper's model instead of the linux profile
//
// Each N runs in a process of its own so that its peak RSS is its own.
//
// --shape cluster: N client hosts instead, each with its own page cache and its own link
// (1250 MB/s) to one NFS server (a 515/375 MB/s disk, writethrough), A applications per host
// (--apps-per-host, 1 by default). Each application reads a 200 MB input from the server in
// 10 MB chunks, computes 1-11 s (staggered) and writes a 50 MB result back: the server's disk
// is saturated from a few clients on, the case where one change used to re-solve every
// client. N counts hosts here:
//
//   pcsim_scaling --shape cluster --max 100000 --budget 0 --callgrind
//   pcsim_scaling --shape cluster --apps-per-host 32 --pipelines 10000   # 320,000 applications
//
// Instructions show the algorithm's growth apart from the machine's caches and page faults:
// each run counts the user-space instructions of its first repetition with the CPU's counter
// (perf_event_open), where there is one (many virtual machines have none: "-"). With
// --callgrind each N is also run once under valgrind's callgrind, which counts the simulation
// alone on any machine (50-100 times slower: N = 10^4 takes about a minute):
//
//   pcsim_scaling --max 10000 --callgrind

#include <pagecache/error.hpp>
#include <pagecache/run.hpp>
#include <pagecache/scenario.hpp>
#include <pagecache/scenario_file.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <fstream>
#include <cstdlib>
#include <cstring>
#include <spawn.h>
#include <string>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

#include <linux/perf_event.h>
#include <sys/ioctl.h>
#include <sys/syscall.h>

#if __has_include(<valgrind/callgrind.h>)
#include <valgrind/callgrind.h>  // client requests: no-ops unless run under callgrind
#define PCSIM_TOGGLE_COLLECT() CALLGRIND_TOGGLE_COLLECT
#else
#define PCSIM_TOGGLE_COLLECT() ((void)0)
#endif

extern char** environ;

namespace {

std::string scenario_text(long pipelines, const std::string& profile) {
  const double n = static_cast<double>(pipelines);
  return fmt::format(R"(title = "scaling: {} pipelines"
profile = "{}"
memory_sample_interval = "60 s"

[[hosts]]
name = "node"
cores = {}
memory = {}
memory_read_bw = "6860 MB/s"
memory_write_bw = "2764 MB/s"
memory_aggregate_read_bw = {}
memory_aggregate_write_bw = {}
memory_first_touch_bw = "6.1 GB/s"

[hosts.page_cache]
dirty_ratio = 0.4
dirty_background_ratio = 0.1

[[hosts.disks]]
name = "disk"
read_bw = {}
write_bw = {}

[pipelines]
count = {}
file_size = "1 GB"
tasks = 3
cpu_time = "1 s"
chunk_size = "100 MB"
)",
                     pipelines, profile, pipelines, static_cast<long long>(n * 2.5e9), n * 10e9, n * 5e9, n * 500e6, n * 500e6,
                     pipelines);
}

// The cluster shape (see the top): a template parsed once (hosts get the profile's defaults
// from the loader), its client host and link copied N times. Built in memory: 10^5 hosts of
// TOML would take longer to read than to simulate.
pagecache::Scenario cluster_scenario(long hosts, long apps_per_host, const std::string& profile) {
  const std::string text = fmt::format(R"(title = "scaling: {} hosts x {} applications over NFS"
profile = "{}"
memory_sample_interval = "60 s"

[[hosts]]
name = "storage"
cores = 32
memory = "250 GiB"
memory_read_bw = "6860 MB/s"
memory_write_bw = "2764 MB/s"
[hosts.page_cache]
mode = "writethrough"
[[hosts.disks]]
name = "nfs-disk"
read_bw = "515 MB/s"
write_bw = "375 MB/s"

[[hosts]]
name = "node"
cores = 2
memory = "8 GiB"
memory_read_bw = "6860 MB/s"
memory_write_bw = "2764 MB/s"
[[hosts.disks]]
name = "ssd"
read_bw = "510 MB/s"
write_bw = "516 MB/s"

[[links]]
name = "net"
bandwidth = "1250 MB/s"
latency = "20 us"
hosts = ["node", "storage"]

# A workload for the loader, replaced below.
[[files]]
name = "template"
size = "1 MB"
host = "storage"
[[apps]]
host = "node"
[[apps.tasks]]
read = "template"
)",
                                       hosts, apps_per_host, profile);
  pagecache::Scenario s = pagecache::parse_scenario(text, "<scaling cluster>", {}, profile);
  const pagecache::HostConfig node = s.hosts.back();
  const pagecache::LinkSpec net = s.links.back();
  s.hosts.pop_back();
  s.links.pop_back();
  s.files.clear();
  s.apps.clear();
  const long apps = hosts * apps_per_host;
  s.hosts.reserve(static_cast<std::size_t>(hosts) + 1);
  s.links.reserve(static_cast<std::size_t>(hosts));
  s.files.reserve(static_cast<std::size_t>(apps) * 2);
  s.apps.reserve(static_cast<std::size_t>(apps));
  for (long h = 1; h <= hosts; ++h) {
    pagecache::HostConfig& host = s.hosts.emplace_back(node);
    host.name = fmt::format("node-{}", h);
    pagecache::LinkSpec& link = s.links.emplace_back(net);
    link.name = fmt::format("net-{}", h);
    link.host_a = host.name;
    for (long a = 1; a <= apps_per_host; ++a) {
      const long k = (h - 1) * apps_per_host + a;
      s.files.push_back({fmt::format("in-{}", k), 200'000'000, "storage", "nfs-disk", false});
      s.files.push_back({fmt::format("out-{}", k), 50'000'000, "storage", "nfs-disk", false});
      pagecache::AppSpec& app = s.apps.emplace_back();
      app.name = std::to_string(k);
      app.host = host.name;
      pagecache::TaskSpec& task = app.tasks.emplace_back();
      task.name = "1";
      task.reads = {fmt::format("in-{}", k)};
      task.compute = 1.0 + 10.0 * static_cast<double>((k * 7919) % apps) / static_cast<double>(apps);
      task.writes = {fmt::format("out-{}", k)};
      task.chunk_size = 10'000'000;
    }
  }
  return s;
}

// The CPU's count of user-space instructions retired by this thread, while it lives.
class InstructionCounter {
 public:
  InstructionCounter() {
    perf_event_attr attr{};
    attr.type = PERF_TYPE_HARDWARE;
    attr.size = sizeof attr;
    attr.config = PERF_COUNT_HW_INSTRUCTIONS;
    attr.disabled = 1;
    attr.exclude_kernel = 1;
    attr.exclude_hv = 1;
    fd_ = static_cast<int>(syscall(SYS_perf_event_open, &attr, 0, -1, -1, 0));
    if (fd_ >= 0) {
      ioctl(fd_, PERF_EVENT_IOC_RESET, 0);
      ioctl(fd_, PERF_EVENT_IOC_ENABLE, 0);
    }
  }
  ~InstructionCounter() {
    if (fd_ >= 0) close(fd_);
  }
  InstructionCounter(const InstructionCounter&) = delete;
  InstructionCounter& operator=(const InstructionCounter&) = delete;
  /// So far; -1 without a counter.
  long long read_count() const {
    long long count = -1;
    if (fd_ < 0 || read(fd_, &count, sizeof count) != static_cast<ssize_t>(sizeof count)) return -1;
    return count;
  }

 private:
  int fd_ = -1;
};

long peak_rss_kb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss;  // kilobytes on Linux
}

// One N in this process: its JSON line on stdout, from repetitions until `budget` seconds
// have been spent (at most 1000, at least one).
int run_one(long pipelines, const std::string& profile, double budget, long apps_per_host) {
  // A scenario for each repetition, handed over to the run (which frees its applications and
  // files once planned, as pcsim run does): built outside the timed run.
  const auto make_scenario = [&] {
    return apps_per_host > 0
               ? cluster_scenario(pipelines, apps_per_host, profile)
               : pagecache::parse_scenario(scenario_text(pipelines, profile), fmt::format("<scaling {}>", pipelines), {}, profile);
  };
  std::size_t applications = 0;
  pagecache::RunOptions options;
  options.cache_contents = false;
  pagecache::RunSummary s;
  std::vector<double> walls;
  double spent = 0.0;
  long long instructions = -1;
  while (walls.size() < 1000 && (walls.empty() || spent < budget)) {
    const bool first = walls.empty();
    pagecache::Scenario scenario = make_scenario();
    applications = scenario.apps.size();
    const InstructionCounter counter;  // a counter of its own: the first repetition's alone
    if (first) PCSIM_TOGGLE_COLLECT();
    const pagecache::RunResult result = pagecache::run_scenario(std::move(scenario), options);
    if (first) {
      PCSIM_TOGGLE_COLLECT();
      instructions = counter.read_count();
    }
    walls.push_back(result.summary.wall_seconds);
    spent += result.summary.wall_seconds;
    s = result.summary;
  }
  std::sort(walls.begin(), walls.end());
  const double best = walls.front();
  const double median = walls[walls.size() / 2];
  const double ops = static_cast<double>(s.chunk_operations);
  fmt::print(
      "{{\"{}\": {}, \"applications\": {}, \"profile\": \"{}\", \"makespan_s\": {:.3f}, \"events\": {}, \"chunk_operations\": {}, "
      "\"repetitions\": {}, \"wall_s\": {:.6f}, \"chunk_ops_per_s\": {:.0f}, \"ns_per_chunk_op\": {:.1f}, "
      "\"median_ns_per_chunk_op\": {:.1f}, \"peak_rss_kb\": {}, \"instructions\": {}, \"instructions_per_chunk_op\": {:.0f}}}\n",
      apps_per_host > 0 ? "hosts" : "pipelines", pipelines, applications, profile, s.makespan, s.events, s.chunk_operations, walls.size(), best, ops / best, best / ops * 1e9,
      median / ops * 1e9, peak_rss_kb(), instructions, instructions < 0 ? -1.0 : static_cast<double>(instructions) / ops);
  return 0;
}

// Runs `[prefix...] self --pipelines N --profile P --budget B` and returns its output line.
std::string run_child(const char* self, long pipelines, const std::string& profile, const std::string& budget, long apps_per_host,
                      const std::vector<std::string>& prefix = {}) {
  int out[2];
  if (pipe(out) != 0) throw std::runtime_error("pipe failed");
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, out[1], STDOUT_FILENO);
  posix_spawn_file_actions_addclose(&actions, out[0]);
  const std::string n = std::to_string(pipelines);
  std::vector<char*> argv;
  for (const std::string& word : prefix) argv.push_back(const_cast<char*>(word.c_str()));
  const std::string per_host = std::to_string(apps_per_host);
  for (const char* word : {self, "--pipelines", n.c_str(), "--profile", profile.c_str(), "--budget", budget.c_str()}) {
    argv.push_back(const_cast<char*>(word));
  }
  if (apps_per_host > 0) {
    for (const char* word : {"--shape", "cluster", "--apps-per-host", per_host.c_str()}) argv.push_back(const_cast<char*>(word));
  }
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int spawned = prefix.empty() ? posix_spawn(&pid, self, &actions, nullptr, argv.data(), environ)
                                     : posix_spawnp(&pid, prefix.front().c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  close(out[1]);
  if (spawned != 0) throw std::runtime_error(fmt::format("cannot run {}: {}", prefix.empty() ? self : prefix.front(), std::strerror(spawned)));
  std::string line;
  char buffer[4096];
  for (ssize_t got; (got = read(out[0], buffer, sizeof buffer)) > 0;) line.append(buffer, static_cast<std::size_t>(got));
  close(out[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) throw std::runtime_error(fmt::format("N = {}: the run failed", pipelines));
  return line;
}

double field(const std::string& line, const std::string& key) {
  const auto at = line.find("\"" + key + "\": ");
  if (at == std::string::npos) throw std::runtime_error("no " + key + " in: " + line);
  return std::strtod(line.c_str() + at + key.size() + 4, nullptr);
}

// N run once under callgrind, collecting the first run_scenario alone: its instruction count.
long long callgrind_instructions(long pipelines, const std::string& profile, long apps_per_host) {
  char self[4096];
  const ssize_t length = readlink("/proc/self/exe", self, sizeof self - 1);
  if (length <= 0) throw std::runtime_error("cannot find this program's path");
  self[length] = '\0';
  const std::string out = fmt::format("/tmp/pcsim-scaling-callgrind-{}-{}.out", getpid(), pipelines);
  run_child(self, pipelines, profile, "0", apps_per_host, {"valgrind", "--tool=callgrind", "--collect-atstart=no", "--callgrind-out-file=" + out, "-q"});
  std::ifstream in(out);
  long long total = -1;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("totals: ", 0) == 0) total = std::strtoll(line.c_str() + 8, nullptr, 10);
  }
  in.close();
  std::remove(out.c_str());
  if (total < 0) throw std::runtime_error(fmt::format("N = {}: no instruction total from callgrind ({})", pipelines, out));
  return total;
}

}  // namespace

int main(int argc, char** argv) {
  long one = 0;
  long max = 100000;
  std::string profile = "linux";
  std::string budget = "1";
  bool callgrind = false;
  bool cluster = false;
  long apps_per_host = 1;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--callgrind") {
      callgrind = true;
    } else if (arg == "--shape" && i + 1 < argc) {
      const std::string shape = argv[++i];
      if (shape != "pipelines" && shape != "cluster") {
        fmt::print(stderr, "pcsim_scaling: --shape is pipelines or cluster, got '{}'\n", shape);
        return 2;
      }
      cluster = shape == "cluster";
    } else if (arg == "--apps-per-host" && i + 1 < argc) {
      const std::string value = argv[++i];
      char* end = nullptr;
      apps_per_host = std::strtol(value.c_str(), &end, 10);
      if (end == value.c_str() || *end != '\0' || apps_per_host < 1) {
        fmt::print(stderr, "pcsim_scaling: --apps-per-host must be a whole number >= 1, got '{}'\n", value);
        return 2;
      }
    } else if ((arg == "--pipelines" || arg == "--max" || arg == "--profile" || arg == "--budget") && i + 1 < argc) {
      const std::string value = argv[++i];
      if (arg == "--profile") {
        profile = value;
      } else if (arg == "--budget") {
        budget = value;
      } else {
        char* end = nullptr;
        const long n = std::strtol(value.c_str(), &end, 10);
        if (end == value.c_str() || *end != '\0' || n < 1) {
          fmt::print(stderr, "pcsim_scaling: {} must be a whole number >= 1, got '{}'\n", arg, value);
          return 2;
        }
        (arg == "--max" ? max : one) = n;
      }
    } else {
      fmt::print(stderr,
                 "usage: {} [--pipelines N | --max N] [--budget SECONDS] [--profile linux|paper] [--shape pipelines|cluster] "
                 "[--apps-per-host A] [--callgrind]\n",
                 argv[0]);
      return 2;
    }
  }
  char* end = nullptr;
  const double budget_s = std::strtod(budget.c_str(), &end);
  if (end == budget.c_str() || *end != '\0' || !(budget_s >= 0.0)) {
    fmt::print(stderr, "pcsim_scaling: --budget must be a number of seconds >= 0, got '{}'\n", budget);
    return 2;
  }
  const long per_host = cluster ? apps_per_host : 0;  // 0: the pipelines shape
  try {
    if (one > 0) return run_one(one, profile, budget_s, per_host);
    std::vector<std::string> lines;
    fmt::print("{:>9} {:>12} {:>12} {:>12} {:>6} {:>10} {:>14} {:>12} {:>12} {:>12} {:>12}{}\n", cluster ? "hosts" : "pipelines", "makespan_s", "events",
               "chunk_ops", "reps", "wall_s", "chunk_ops/s", "ns/chunk_op", "median_ns", "peak_RSS_MB", "instr/op", callgrind ? "  callgrind_instr/op" : "");
    for (long n = 10; n <= max; n *= 10) {
      const std::string line = run_child("/proc/self/exe", n, profile, budget, per_host);
      lines.push_back(line);
      const double per_op = field(line, "instructions_per_chunk_op");
      std::string counted;
      if (callgrind) {
        const long long total = callgrind_instructions(n, profile, per_host);
        counted = fmt::format("  {:>19.0f}", static_cast<double>(total) / field(line, "chunk_operations"));
        lines.back().insert(lines.back().rfind('}'), fmt::format(", \"callgrind_instructions\": {}", total));
      }
      fmt::print("{:>9} {:>12.1f} {:>12.0f} {:>12.0f} {:>6.0f} {:>10.4f} {:>14.0f} {:>12.1f} {:>12.1f} {:>12.1f} {:>12}{}\n", n,
                 field(line, "makespan_s"), field(line, "events"), field(line, "chunk_operations"), field(line, "repetitions"),
                 field(line, "wall_s"), field(line, "chunk_ops_per_s"), field(line, "ns_per_chunk_op"),
                 field(line, "median_ns_per_chunk_op"), field(line, "peak_rss_kb") / 1024.0,
                 per_op < 0.0 ? std::string("-") : fmt::format("{:.0f}", per_op), counted);
      std::fflush(stdout);
    }
    fmt::print("\n");
    for (const std::string& line : lines) fmt::print("{}", line);
  } catch (const std::exception& e) {
    fmt::print(stderr, "pcsim_scaling: {}\n", e.what());
    return 1;
  }
  return 0;
}
