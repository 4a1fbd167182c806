#include "scenario/limits.hpp"
#include "scenario/route_index.hpp"

#include <pagecache/units.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string_view>
#include <unordered_map>

namespace pagecache {

ScenarioLimits ScenarioLimits::forced() {
  ScenarioLimits l;
  l.max_tasks = 500'000'000;  // three timeline rows each, indexed by 32 bits
  l.max_files = 1'000'000'000;
  l.max_hosts = 1'000'000'000;
  l.max_events = std::numeric_limits<double>::infinity();
  l.max_simulated_time = units::kMaxSeconds;
  l.max_memory_rows = std::numeric_limits<double>::infinity();
  return l;
}

}  // namespace pagecache

namespace pagecache::scenario {

std::string limits_hint(const ScenarioLimits& limits) {
  const ScenarioLimits forced = ScenarioLimits::forced();
  const bool below = limits.max_tasks < forced.max_tasks || limits.max_files < forced.max_files || limits.max_hosts < forced.max_hosts ||
                     limits.max_events < forced.max_events ||
                     limits.max_simulated_time < forced.max_simulated_time || limits.max_memory_rows < forced.max_memory_rows;
  return below ? " without --force" : "";
}

namespace {

// The longest stretch found so far, and the key to blame for it.
struct Longest {
  double seconds = 0.0;
  const Origin* origin = nullptr;
  std::string key;
  std::string what;  // what takes that long, for the message

  void offer(double s, const Origin& o, std::string k, std::string w) {
    if (s > seconds) *this = {s, &o, std::move(k), std::move(w)};
  }
};

// What the tasks ask of the platform, summed per disk, link and host.
class Demand {
 public:
  explicit Demand(const Scenario& s) : s_(s), disk_read_(s.hosts.size()), disk_write_(s.hosts.size()), memory_read_(s.hosts.size()),
                                       memory_write_(s.hosts.size()), link_(s.links.size()) {
    for (std::size_t h = 0; h < s.hosts.size(); ++h) {
      disk_read_[h].assign(s.hosts[h].disks.size(), 0.0);
      disk_write_[h].assign(s.hosts[h].disks.size(), 0.0);
      host_index_.emplace(s.hosts[h].name, h);
    }
    // Where each file is, found once: a scenario may have 10^6 of them.
    place_.reserve(s.files.size());
    file_index_.reserve(s.files.size());
    for (std::size_t f = 0; f < s.files.size(); ++f) {
      const std::size_t h = host_of(s.files[f].host);
      place_.push_back({h, disk_of(h, s.files[f].disk)});
      file_index_.emplace(s.files[f].name, f);
    }
  }

  std::size_t host_of(const std::string& name) const { return host_index_.at(name); }

  /// Adds one task's reads and writes on host `h`; returns its chunk operations.
  double add(std::size_t h, const TaskSpec& t) {
    double operations = 0.0;
    for (int writing = 0; writing < 2; ++writing) {
      for (const std::string& name : writing ? t.writes : t.reads) {
        const std::size_t f = file_index_.at(name);
        const double bytes = static_cast<double>(s_.files[f].size);
        const auto [fh, fd] = place_[f];
        (writing ? disk_write_ : disk_read_)[fh][fd] += bytes;
        (writing ? memory_write_ : memory_read_)[h] += bytes;
        if (fh != h) {
          for (const std::size_t l : route_of(h, fh)) link_[l] += bytes;
        }
        operations += std::ceil(bytes / static_cast<double>(t.chunk_size));
      }
    }
    return operations;
  }

  /// The busiest disk, link and memory: what each must move at its bandwidth.
  void offer_devices(const Origins& o, Longest& longest) const {
    for (std::size_t h = 0; h < s_.hosts.size(); ++h) {
      const HostConfig& host = s_.hosts[h];
      for (std::size_t d = 0; d < host.disks.size(); ++d) {
        const double reading = disk_read_[h][d] / host.disks[d].read_bw;
        const double writing = disk_write_[h][d] / host.disks[d].write_bw;
        longest.offer(reading + writing, o.disks[h][d], reading >= writing ? "read_bw" : "write_bw",
                      fmt::format("disk '{}' of host '{}' moving {}", host.disks[d].name, host.name, bytes(disk_read_[h][d] + disk_write_[h][d])));
      }
      const double reading = memory_read_[h] / host.memory_bandwidth.aggregate_read;
      const double writing = memory_write_[h] / host.memory_bandwidth.aggregate_write;
      const char* key = reading >= writing ? (o.hosts[h].has("memory_aggregate_read_bw") ? "memory_aggregate_read_bw" : "memory_read_bw")
                                           : (o.hosts[h].has("memory_aggregate_write_bw") ? "memory_aggregate_write_bw" : "memory_write_bw");
      longest.offer(reading + writing, o.hosts[h], key,
                    fmt::format("the memory of host '{}' copying {}", host.name, bytes(memory_read_[h] + memory_write_[h])));
    }
    for (std::size_t l = 0; l < s_.links.size(); ++l) {
      longest.offer(link_[l] / s_.links[l].bandwidth, o.links[l], "bandwidth", fmt::format("link '{}' carrying {}", s_.links[l].name, bytes(link_[l])));
    }
  }

  /// Hosts that write back dirty data to their disks, by index.
  std::vector<std::size_t> writeback_hosts() const {
    std::vector<std::size_t> out;
    for (std::size_t h = 0; h < s_.hosts.size(); ++h) {
      const bool writes = std::any_of(disk_write_[h].begin(), disk_write_[h].end(), [](double b) { return b > 0.0; });
      if (writes && s_.hosts[h].cache.write_mode == WriteMode::Writeback) out.push_back(h);
    }
    return out;
  }

 private:
  static std::string bytes(double b) { return units::format_size(static_cast<std::int64_t>(std::min(b, 9e18))); }

  std::size_t disk_of(std::size_t host, const std::string& disk) const {
    const auto& disks = s_.hosts[host].disks;
    return static_cast<std::size_t>(std::find_if(disks.begin(), disks.end(), [&](const DiskSpec& d) { return d.name == disk; }) - disks.begin());
  }
  // The links between two hosts, by index, looked up once per pair.
  const std::vector<std::size_t>& route_of(std::size_t a, std::size_t b) {
    auto [it, added] = routes_.try_emplace({a, b});
    if (added) {
      for (const LinkSpec* l : route_index_.between(s_.hosts[a].name, s_.hosts[b].name)) {
        it->second.push_back(static_cast<std::size_t>(l - s_.links.data()));
      }
    }
    return it->second;
  }

  const Scenario& s_;
  std::unordered_map<std::string_view, std::size_t> host_index_;  // a cluster's 10^5 hosts: no scan per name
  std::unordered_map<std::string_view, std::size_t> file_index_;
  std::vector<std::pair<std::size_t, std::size_t>> place_;  // per file: its host and disk
  std::vector<std::vector<double>> disk_read_, disk_write_;
  std::vector<double> memory_read_, memory_write_;
  std::vector<double> link_;
  std::map<std::pair<std::size_t, std::size_t>, std::vector<std::size_t>> routes_;
  RouteIndex route_index_{s_};
};

// The key setting a task's chunk size, where it is written: the task's own, else its
// application's or workflow's, else (the default) the task's table.
std::pair<const Origin*, const char*> chunk_key(const Origin& task, const Origin& owner) {
  if (task.has("chunk_size")) return {&task, "chunk_size"};
  if (owner.has("chunk_size")) return {&owner, "chunk_size"};
  return {&task, "chunk_size"};
}

}  // namespace

void check_limits(const Scenario& s, const Origins& o, const ScenarioLimits& limits) {
  const std::string hint = limits_hint(limits);
  std::size_t tasks = 0;
  for (const AppSpec& a : s.apps) tasks += a.tasks.size();
  for (const WorkflowSpec& w : s.workflows) tasks += w.tasks.size();
  if (static_cast<double>(tasks) > static_cast<double>(limits.max_tasks)) {
    o.root.fail_table(fmt::format("{} tasks, more than the {} a run may have{}", tasks, limits.max_tasks, hint));
  }
  if (static_cast<double>(s.files.size()) > static_cast<double>(limits.max_files)) {
    o.root.fail_table(fmt::format("{} files, more than the {} a run may have{}", s.files.size(), limits.max_files, hint));
  }
  if (static_cast<double>(s.hosts.size()) > static_cast<double>(limits.max_hosts)) {
    // Most likely a host group's count: blame it.
    const auto group = std::find_if(o.host_groups.begin(), o.host_groups.end(),
                                    [&](const auto& g) { return static_cast<double>(g.second.second) > static_cast<double>(limits.max_hosts) / 2; });
    const std::string message = fmt::format("{} hosts, more than the {} a run may have{}", s.hosts.size(), limits.max_hosts, hint);
    if (group != o.host_groups.end()) o.hosts[group->second.first].fail("count", message);
    o.root.fail_table(message);
  }

  Demand demand(s);
  Longest longest;
  double operations = 0.0;
  double most_operations = -1.0;
  std::pair<const Origin*, const char*> most_operations_key{nullptr, nullptr};
  // A task's operations, and its compute as a stretch an application or workflow must run.
  auto add_tasks = [&](std::size_t host, const std::vector<TaskSpec>& list, const Origin& owner, const auto& task_origin,
                       double cores, const char* compute_key, const std::string& who) {
    double compute = 0.0;
    double longest_compute = -1.0;
    const Origin* longest_task = nullptr;
    for (std::size_t t = 0; t < list.size(); ++t) {
      const double ops = demand.add(host, list[t]);
      operations += ops;
      if (ops > most_operations) {
        most_operations = ops;
        most_operations_key = chunk_key(task_origin(t), owner);
      }
      compute += list[t].compute;
      if (list[t].compute > longest_compute) {
        longest_compute = list[t].compute;
        longest_task = &task_origin(t);
      }
    }
    longest.offer(compute / cores, *longest_task, compute_key, fmt::format("{} computing {:g} s", who, compute));
  };
  for (std::size_t a = 0; a < s.apps.size(); ++a) {
    const bool pipeline = o.from_pipelines(a);
    add_tasks(demand.host_of(s.apps[a].host), s.apps[a].tasks, o.app(a), [&](std::size_t t) -> const Origin& { return o.app_task(a, t); }, 1.0,
              pipeline ? "cpu_time" : "compute", fmt::format("application '{}'", s.apps[a].name));
  }
  for (std::size_t w = 0; w < s.workflows.size(); ++w) {
    // The workflow's I/O counted as if on its first host (a task may run on another: the
    // estimate of what its devices move is then pessimistic), its compute over all its hosts'
    // cores.
    const WorkflowSpec& flow = s.workflows[w];
    int cores = 0;
    for (const std::string& name : flow.hosts) cores += s.hosts[demand.host_of(name)].cores;
    add_tasks(demand.host_of(flow.hosts.front()), flow.tasks, o.workflows[w],
              [&](std::size_t t) -> const Origin& { return o.workflow_tasks[w][t]; }, static_cast<double>(cores), "compute",
              fmt::format("workflow '{}' on {} cores", flow.name, cores));
  }
  demand.offer_devices(o, longest);

  const double simulated = longest.seconds;
  if (simulated > limits.max_simulated_time) {
    longest.origin->fail(longest.key, fmt::format("the run would take at least about {:.3g} s of simulated time ({}), more than the {:g} s "
                                                  "a run may take{}",
                                                  simulated, longest.what, limits.max_simulated_time, hint));
  }

  // Events: three per chunk operation, and a flusher's wake-up every writeback_interval.
  double wakeups = 0.0;
  std::size_t busiest_flusher = 0;
  for (std::size_t h : demand.writeback_hosts()) {
    const double w = simulated / s.hosts[h].cache.writeback_interval;
    if (w > wakeups) busiest_flusher = h;
    wakeups = std::max(wakeups, w);
  }
  const double events = 3.0 * operations + wakeups * static_cast<double>(demand.writeback_hosts().size());
  if (events > limits.max_events) {
    if (3.0 * operations >= wakeups) {
      most_operations_key.first->fail(most_operations_key.second,
                                      fmt::format("the run would take about {:.3g} events for {:.3g} chunk operations (each file's "
                                                  "bytes over its task's chunk size, for every read and write), more than the {:.3g} "
                                                  "a run may take{}: a larger chunk_size makes fewer",
                                                  events, operations, limits.max_events, hint));
    }
    o.page_caches[busiest_flusher].fail("writeback_interval",
                                        fmt::format("the flusher of host '{}' would wake about {:.3g} times over the {:.3g} s the run "
                                                    "takes, more than the {:.3g} events a run may take{}",
                                                    s.hosts[busiest_flusher].name, wakeups, simulated, limits.max_events, hint));
  }

  // memory.csv: a row per host at most at every change (a few per chunk operation).
  const double hosts = static_cast<double>(s.hosts.size());
  const double changes = 2.0 * operations + hosts;
  const double interval = s.memory_sample_interval;
  const double rows = interval > 0.0 ? std::min(changes, hosts * (simulated / interval + 1.0)) : changes;
  if (rows > limits.max_memory_rows) {
    o.root.fail("memory_sample_interval",
                fmt::format("memory.csv would hold about {:.3g} rows ({}), more than the {:.3g} a run may write{}: a longer interval "
                            "makes fewer",
                            rows, interval > 0.0 ? fmt::format("a row per host every {:g} s over {:.3g} s", interval, simulated) : "a row at every change",
                            limits.max_memory_rows, hint));
  }
}

}  // namespace pagecache::scenario
