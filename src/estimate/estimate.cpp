#include "estimate/estimate.hpp"
#include "estimate/loads.hpp"

#include "cache/policy.hpp"
#include "estimate/route_index.hpp"
#include "workload/access_pattern.hpp"

#include <pagecache/units.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

namespace pagecache::estimate {

namespace {

std::string bytes_text(double b) { return units::format_size(static_cast<std::int64_t>(std::min(b, 9e18))); }

class Estimator {
 public:
  explicit Estimator(const Scenario& s) : s_(s), loads_(s.hosts.size()), link_bytes_(s.links.size(), 0.0) {
    for (std::size_t h = 0; h < s.hosts.size(); ++h) {
      const std::size_t disks = s.hosts[h].disks.size();
      loads_[h].disk_read.assign(disks, 0.0);
      loads_[h].disk_write.assign(disks, 0.0);
      loads_[h].dirtied.assign(disks, 0.0);
      host_index_.emplace(s.hosts[h].name, h);
      throttles_.push_back(s.hosts[h].cache.write_mode == WriteMode::Writeback && cache::make_policy(s.hosts[h].cache)->throttles_writers());
    }
    // Where each file and file set is, found once: a scenario may have 10^6 files.
    const auto place = [&](const std::string& host, const std::string& disk) {
      const std::size_t h = host_index_.at(host);
      const auto& disks = s.hosts[h].disks;
      const auto d = std::find_if(disks.begin(), disks.end(), [&](const DiskSpec& x) { return x.name == disk; }) - disks.begin();
      return std::make_pair(h, static_cast<std::size_t>(d));
    };
    place_.reserve(s.files.size());
    file_index_.reserve(s.files.size());
    for (std::size_t f = 0; f < s.files.size(); ++f) {
      place_.push_back(place(s.files[f].host, s.files[f].disk));
      file_index_.emplace(s.files[f].name, f);
    }
    for (std::size_t f = 0; f < s.file_sets.size(); ++f) {
      set_place_.push_back(place(s.file_sets[f].host, s.file_sets[f].disk));
      set_index_.emplace(s.file_sets[f].name, f);
    }
  }

  RunEstimate run() {
    for (std::size_t a = 0; a < s_.apps.size(); ++a) add_application(a);
    for (std::size_t w = 0; w < s_.workflows.size(); ++w) add_workflow(w);
    offer_devices();
    e_.transfer_events += static_cast<double>(s_.apps.size());  // each application's start
    add_writeback_hosts();
    add_sampler();
    return std::move(e_);
  }

 private:
  // The links between two hosts, by index, and their latency, looked up once per pair.
  struct Route {
    std::vector<std::size_t> links;
    double latency = 0.0;
    std::size_t slowest = 0;  // the link of highest latency
  };
  const Route& route_of(std::size_t a, std::size_t b) {
    auto [it, added] = routes_.try_emplace({a, b});
    if (added) {
      for (const LinkSpec* l : route_index_.between(s_.hosts[a].name, s_.hosts[b].name)) {
        const auto index = static_cast<std::size_t>(l - s_.links.data());
        if (it->second.links.empty() || l->latency > s_.links[it->second.slowest].latency) it->second.slowest = index;
        it->second.links.push_back(index);
        it->second.latency += l->latency;
      }
    }
    return it->second;
  }

  struct TaskCost {
    double operations = 0.0;
    double memory = 0.0;  // application memory it holds: its declared memory, or what it reads
  };

  // What one task does on host `h`, added to the hosts' loads and to the events. `latency` gets
  // the seconds it waits for its routes' latencies, `slowest` the link of highest latency it
  // crosses.
  TaskCost add_task(std::size_t h, const TaskSpec& t, StreamWrites& writes, double& latency, std::size_t& slowest) {
    double operations = 0.0;
    double read_bytes = 0.0;
    const auto chunks = [&](double bytes) { return std::ceil(bytes / static_cast<double>(t.chunk_size)); };
    // A file read or written (or a file set's samples): `bytes` in `ops` chunks, stored at (fh, fd).
    const auto move = [&](std::size_t fh, std::size_t fd, double bytes, double ops, bool writing) {
      HostLoad& server = loads_[fh];
      (writing ? server.disk_write : server.disk_read)[fd] += bytes;
      (writing ? loads_[h].memory_write : loads_[h].memory_read) += bytes;
      const bool remote = fh != h;
      // The server's cache takes what is written to it, unless a local write bypasses it.
      const bool dirties = writing && s_.hosts[fh].cache.write_mode == WriteMode::Writeback && (remote || !t.direct_io);
      if (remote) {
        const Route& route = route_of(h, fh);
        for (const std::size_t l : route.links) link_bytes_[l] += bytes;
        if (route.latency > 0.0) {
          if (latency == 0.0 || s_.links[route.slowest].latency > s_.links[slowest].latency) slowest = route.slowest;
          latency += ops * route.latency;
        }
        e_.transfer_events += ops * (kRemoteEvents + (route.latency > 0.0 ? 1.0 : 0.0));
        if (dirties) e_.transfer_events += ops * kCachedWriteEvents;
      } else if (!writing) {
        e_.transfer_events += ops * kLocalReadEvents;
      } else {
        e_.transfer_events += ops * (dirties ? kCachedWriteEvents : kDeviceWriteEvents);
      }
      if (dirties) {
        server.dirtied[fd] += bytes;
        server.dirtied_ops += ops;
        writes.bytes[fh] += bytes;
        writes.ops[fh] += ops;
      }
      operations += ops;
    };
    for (int writing = 0; writing < 2; ++writing) {
      for (const std::string& name : writing ? t.writes : t.reads) {
        const std::size_t f = file_index_.at(name);
        const double bytes = static_cast<double>(s_.files[f].size);
        if (!writing) read_bytes += bytes;
        move(place_[f].first, place_[f].second, bytes, chunks(bytes), writing != 0);
      }
    }
    const double largest_sample = add_accesses(t, move, operations);
    // One write phase per host whose cache it writes into.
    std::map<std::size_t, bool> written;
    for (const std::string& name : t.writes) {
      const std::size_t fh = place_[file_index_.at(name)].first;
      if (s_.hosts[fh].cache.write_mode == WriteMode::Writeback && (fh != h || !t.direct_io)) written[fh] = true;
    }
    for (const auto& [host, yes] : written) writes.phases[host] += 1.0;
    // Its start (a workflow's: see add_workflow), computation, fsyncs and deletions.
    if (t.compute > 0.0) e_.transfer_events += kFlowEvents;
    if (t.fsync) e_.transfer_events += kFlowEvents * static_cast<double>(t.writes.size());
    e_.transfer_events += static_cast<double>(t.deletes.size());
    loads_[h].cpu += t.compute * static_cast<double>(t.cores);
    return {operations, std::max(static_cast<double>(t.memory), read_bytes + largest_sample)};
  }

  // A task's accesses: each sample a read of a whole file of its set (`move`, add_task's) and an
  // event at least. Returns the largest sample.
  template <typename Move>
  double add_accesses(const TaskSpec& t, const Move& move, double& operations) {
    const double before = operations;
    double most = -1.0, largest = 0.0;
    std::optional<std::size_t> busiest;
    for (std::size_t i = 0; i < t.accesses.size(); ++i) {
      const AccessSpec& a = t.accesses[i];
      if (!a.file.empty()) {
        const double ops_before = operations;
        largest = std::max(largest, add_file_access(a, move));
        if (operations - ops_before > most) {
          most = operations - ops_before;
          busiest = i;
        }
        continue;
      }
      const std::size_t set = set_index_.at(a.file_set);
      const double samples = static_cast<double>(a.count > 0 ? a.count : s_.file_sets[set].count) * static_cast<double>(a.repeat);
      const double size = static_cast<double>(s_.file_sets[set].size), ops_before = operations;
      move(set_place_[set].first, set_place_[set].second, samples * size, samples * std::max(1.0, std::ceil(size / static_cast<double>(t.chunk_size))), false);
      e_.transfer_events += samples;  // each sample's start
      if (operations - ops_before > most) {
        most = operations - ops_before;
        busiest = i;
      }
      largest = std::max(largest, size);
    }
    if (operations > most_ops_) access_of_most_ops_ = operations - before > before ? busiest : std::nullopt;
    return largest;
  }

  // An access of parts of one file: each request an operation as a chunk's (`move`, add_task's),
  // read or written where the file is. Returns the buffer a read holds meanwhile (a request's).
  template <typename Move>
  double add_file_access(const AccessSpec& a, const Move& move) {
    const std::size_t f = file_index_.at(a.file);
    const workload::RequestPattern pattern = workload::request_pattern(a);
    const double epochs = static_cast<double>(a.repeat);
    const double requests = static_cast<double>(workload::RequestStream(pattern).per_epoch()) * epochs;
    const bool writing = a.mode != AccessMode::Read;
    move(place_[f].first, place_[f].second, workload::bytes_per_epoch(pattern) * epochs, requests, writing);
    return writing ? 0.0 : static_cast<double>(a.request);
  }

  void note_operations(double ops, TaskAt at) {
    e_.chunk_operations += ops;
    if (ops > most_ops_) {
      most_ops_ = ops;
      e_.most_operations = at;
      e_.most_operations_access = access_of_most_ops_;
    }
  }

  // An application: its tasks one after the other on its host, one write stream.
  void add_application(std::size_t a) {
    const AppSpec& app = s_.apps[a];
    const std::size_t h = host_index_.at(app.host);
    StreamWrites writes;
    double compute = 0.0, latency = 0.0, longest_compute = -1.0, most_memory = 0.0;
    std::size_t slowest = 0, longest_task = 0;
    for (std::size_t t = 0; t < app.tasks.size(); ++t) {
      const TaskCost cost = add_task(h, app.tasks[t], writes, latency, slowest);
      note_operations(cost.operations, {false, a, t});
      most_memory = std::max(most_memory, cost.memory);
      compute += app.tasks[t].compute;
      if (app.tasks[t].compute > longest_compute) {
        longest_compute = app.tasks[t].compute;
        longest_task = t;
      }
    }
    loads_[h].anonymous += most_memory;
    add_stream(writes, 1.0);
    if (app.memory_max > 0) add_group(writes, static_cast<double>(app.memory_max) - most_memory);
    const bool waiting = latency > compute;
    offer({.kind = Stretch::Kind::Application, .seconds = compute + latency, .index = a, .latency = waiting, .link = slowest,
           .task = longest_task,
           .what = waiting ? fmt::format("application '{}' waiting {:.3g} s for the latency of its routes", app.name, latency)
                           : fmt::format("application '{}' computing {:g} s", app.name, compute)});
  }

  // A workflow: its tasks spread over its hosts, those without a host of their own in
  // proportion to the hosts' cores (the first host with room takes a ready task), as many at
  // once as their cores allow.
  void add_workflow(std::size_t w) {
    const WorkflowSpec& flow = s_.workflows[w];
    if (flow.tasks.empty() || flow.hosts.empty()) return;  // one built in code may be: nothing runs
    double cores = 0.0;
    for (const std::string& name : flow.hosts) cores += static_cast<double>(s_.hosts[host_index_.at(name)].cores);
    double task_cores = 0.0, shared = 0.0;
    for (const TaskSpec& t : flow.tasks) {
      task_cores += static_cast<double>(t.cores);
      shared += t.host.empty() ? 1.0 : 0.0;
    }
    // The shared tasks in blocks, each host's as large as its share of the cores.
    std::size_t block_host = 0;
    double block_left = 0.0;
    const auto next_shared = [&]() -> std::size_t {
      while (block_left <= 0.0 && block_host < flow.hosts.size()) {
        block_left += shared * static_cast<double>(s_.hosts[host_index_.at(flow.hosts[block_host])].cores) / cores;
        ++block_host;
      }
      block_left -= 1.0;
      return host_index_.at(flow.hosts[block_host - 1]);
    };
    // Tasks running at once: as many as the cores hold, on average.
    const double at_once = std::clamp(cores / std::max(1.0, task_cores / static_cast<double>(flow.tasks.size())), 1.0,
                                      static_cast<double>(flow.tasks.size()));
    StreamWrites writes;
    std::vector<double> memory(s_.hosts.size(), 0.0), placed(s_.hosts.size(), 0.0);
    double compute = 0.0, latency = 0.0, longest_compute = -1.0;
    std::size_t slowest = 0, longest_task = 0;
    for (std::size_t t = 0; t < flow.tasks.size(); ++t) {
      const TaskSpec& task = flow.tasks[t];
      const std::size_t h = task.host.empty() ? next_shared() : host_index_.at(task.host);
      const TaskCost cost = add_task(h, task, writes, latency, slowest);
      note_operations(cost.operations, {true, w, t});
      memory[h] += cost.memory;
      placed[h] += 1.0;
      compute += task.compute;
      if (task.compute > longest_compute) {
        longest_compute = task.compute;
        longest_task = t;
      }
    }
    e_.transfer_events += kWorkflowTaskStartEvents * static_cast<double>(flow.tasks.size());
    for (std::size_t h = 0; h < s_.hosts.size(); ++h) {
      // The tasks running here at once hold their memory together.
      if (placed[h] > 0.0) loads_[h].anonymous += memory[h] / placed[h] * std::min(placed[h], static_cast<double>(s_.hosts[h].cores));
    }
    // Its writes into a cache come from as many writers as run at once, in that many fewer rounds.
    for (auto& [host, phases] : writes.phases) phases /= at_once;
    add_stream(writes, at_once);
    const bool waiting = latency > compute;
    offer({.kind = Stretch::Kind::Workflow, .seconds = (compute + latency) / at_once, .index = w, .latency = waiting, .link = slowest,
           .task = longest_task,
           .what = waiting ? fmt::format("workflow '{}' waiting {:.3g} s for the latency of its routes, {:.3g} tasks at once", flow.name,
                                         latency, at_once)
                           : fmt::format("workflow '{}' on {:g} cores computing {:g} s", flow.name, cores, compute)});
  }

  // A stream's writers and write phases, on the hosts whose caches it writes into.
  void add_stream(const StreamWrites& writes, double writers) {
    for (const auto& [host, bytes] : writes.bytes) {
      HostLoad& load = loads_[host];
      load.writers += std::min(writers, writes.ops.at(host));
      load.write_rounds = std::max(load.write_rounds, writes.phases.count(host) != 0 ? writes.phases.at(host) : 1.0);
    }
  }

  // An application's memory group is a writeback domain of its own (docs/model.md §6.11): its
  // one writer is throttled against the group's limits, whatever the host's.
  void add_group(const StreamWrites& writes, double room) {
    for (const auto& [host, bytes] : writes.bytes) {
      if (!throttles_[host]) continue;
      const CacheSettings& c = s_.hosts[host].cache;
      const double throttled = bytes - setpoint_share(c) * std::max(0.0, room);
      if (throttled <= 0.0) continue;
      const double chunk = bytes / writes.ops.at(host);
      loads_[host].group_pauses += std::max(throttled / chunk, throttled / slowest_write(host) / kMaxPause);
    }
  }

  // The kernel's setpoint, as a fraction of dirtyable memory: halfway between the freerun
  // ceiling (the mean of the two thresholds) and the limit (DirtyThrottle).
  static double setpoint_share(const CacheSettings& c) { return (c.dirty_background_ratio + 3.0 * c.dirty_ratio) / 4.0; }

  double slowest_write(std::size_t h) const {
    double bw = 0.0;
    for (const DiskSpec& d : s_.hosts[h].disks) bw = bw == 0.0 ? d.write_bw : std::min(bw, d.write_bw);
    return bw;
  }

  void offer(Stretch s) {
    if (s.seconds > e_.longest.seconds) e_.longest = std::move(s);
  }

  // The busiest disk, memory, cores and link: what each must move or compute.
  void offer_devices() {
    for (std::size_t h = 0; h < s_.hosts.size(); ++h) {
      const HostConfig& host = s_.hosts[h];
      const HostLoad& load = loads_[h];
      for (std::size_t d = 0; d < host.disks.size(); ++d) {
        const double reading = load.disk_read[d] / host.disks[d].read_bw;
        const double writing = load.disk_write[d] / host.disks[d].write_bw;
        offer({.kind = Stretch::Kind::Disk, .seconds = reading + writing, .index = h, .disk = d, .reading = reading >= writing,
               .what = fmt::format("disk '{}' of host '{}' moving {}", host.disks[d].name, host.name,
                                   bytes_text(load.disk_read[d] + load.disk_write[d]))});
      }
      const double reading = load.memory_read / host.memory_bandwidth.aggregate_read;
      const double writing = load.memory_write / host.memory_bandwidth.aggregate_write;
      offer({.kind = Stretch::Kind::Memory, .seconds = reading + writing, .index = h, .reading = reading >= writing,
             .what = fmt::format("the memory of host '{}' copying {}", host.name, bytes_text(load.memory_read + load.memory_write))});
      offer({.kind = Stretch::Kind::Cores, .seconds = load.cpu / static_cast<double>(host.cores), .index = h,
             .what = fmt::format("the {} cores of host '{}' computing {:g} s", host.cores, host.name, load.cpu)});
    }
    for (std::size_t l = 0; l < s_.links.size(); ++l) {
      offer({.kind = Stretch::Kind::Link, .seconds = link_bytes_[l] / s_.links[l].bandwidth, .index = l,
             .what = fmt::format("link '{}' carrying {}", s_.links[l].name, bytes_text(link_bytes_[l]))});
    }
  }

  // Per host whose cache holds dirty data: its flusher's wake-ups, and its writers' pauses when
  // dirty throttling holds them (docs/model.md §6.4).
  void add_writeback_hosts() {
    const double simulated = e_.longest.seconds;
    for (std::size_t h = 0; h < s_.hosts.size(); ++h) {
      const HostLoad& load = loads_[h];
      const HostConfig& host = s_.hosts[h];
      double dirtied = 0.0, drain = 0.0;  // bytes, and seconds to write them to their disks
      for (std::size_t d = 0; d < host.disks.size(); ++d) {
        dirtied += load.dirtied[d];
        drain += load.dirtied[d] / host.disks[d].write_bw;
      }
      if (dirtied <= 0.0) continue;
      // The flusher wakes at each tick while it has dirty data and nothing to write: while each
      // write phase's data waits for its expiry (unless background writeback takes it first).
      // Writing, it does not tick: a tick past is followed by the next at once.
      const CacheSettings& c = host.cache;
      const double waiting = std::min(simulated + c.dirty_expire, load.write_rounds * c.dirty_expire) + c.writeback_interval;
      const double wakeups = waiting / c.writeback_interval;
      e_.flusher_events += wakeups;
      if (wakeups > e_.busiest_flusher_wakeups) {
        e_.busiest_flusher_wakeups = wakeups;
        e_.busiest_flusher = h;
      }
      if (!throttles_[h]) continue;
      // Throttled writers: past the setpoint of dirtyable memory (what the tasks' buffers
      // leave), the rest waits for the disks, each writer pausing a second at a time, and at
      // least once per chunk.
      const double usable = static_cast<double>(host.memory - host.memory_in_use);
      const double dirtyable = std::max(0.0, usable - std::min(usable, load.anonymous));
      const double throttled = std::max(0.0, dirtied - setpoint_share(c) * dirtyable);
      const double chunks = throttled / (dirtied / load.dirtied_ops);
      const double writers = std::clamp(load.writers, 1.0, load.dirtied_ops);
      const double pauses = std::max(load.group_pauses, std::max(chunks, writers * throttled / dirtied * drain / kMaxPause));
      e_.throttle_events += pauses;
      if (pauses > e_.most_throttled_pauses) {
        e_.most_throttled_pauses = pauses;
        e_.most_throttled_host = h;
      }
    }
  }

  // The memory sampler wakes at each tick while memory changes, and waits for a change when it
  // does not: at most a tick or two per change, a few per chunk operation.
  void add_sampler() {
    const double simulated = e_.longest.seconds;
    const double hosts = static_cast<double>(s_.hosts.size());
    const double changes = 2.0 * e_.chunk_operations + hosts;
    const double interval = s_.memory_sample_interval;
    if (interval > 0.0) e_.sampler_events = std::min(simulated / interval + 1.0, changes);
    e_.memory_rows = interval > 0.0 ? std::min(changes, hosts * (simulated / interval + 1.0)) : changes;
  }

  const Scenario& s_;
  RunEstimate e_;
  std::vector<HostLoad> loads_;
  std::vector<double> link_bytes_;
  std::vector<bool> throttles_;  // per host: its writers are throttled (DirtyThrottle)
  std::unordered_map<std::string_view, std::size_t> host_index_;  // a cluster's 10^5 hosts: no scan per name
  std::unordered_map<std::string_view, std::size_t> file_index_;
  std::vector<std::pair<std::size_t, std::size_t>> place_;  // per file: its host and disk
  std::unordered_map<std::string_view, std::size_t> set_index_;
  std::vector<std::pair<std::size_t, std::size_t>> set_place_;  // per file set: its host and disk
  std::map<std::pair<std::size_t, std::size_t>, Route> routes_;
  RouteIndex route_index_{s_};
  double most_ops_ = -1.0;
  std::optional<std::size_t> access_of_most_ops_;  // of the task add_task saw last
};

}  // namespace

RunEstimate estimate_run(const Scenario& s) { return Estimator(s).run(); }

}  // namespace pagecache::estimate
