// run_scenario: builds the platform of a resolved scenario, runs its applications and
// workflows to the end, and collects the timeline, the memory profile and the cache contents.

#include <pagecache/error.hpp>
#include <pagecache/host.hpp>
#include <pagecache/run.hpp>
#include <pagecache/units.hpp>

#include "workload/core_scheduler.hpp"
#include "workload/result_recorder.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <deque>
#include <iterator>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <tuple>
#include <unordered_map>

namespace pagecache {

namespace {

// A file where it is stored (its name is its host's: Host::file_name).
struct PlacedFile {
  Host* host;
  FileRef ref;
};

// A task as its run reads it, made once before the run, the plans of all tasks side by side,
// so that an I/O phase looks no name up and reads no cold string. Its files are ranges of one
// array of indices into the runner's array of placed files, in the order of the task's lists.
struct TaskPlan {
  std::uint32_t reads = 0;  // first read; the writes follow the reads, the deletes the writes
  std::uint32_t writes = 0;
  std::uint32_t deletes = 0;
  std::uint32_t end = 0;
  std::int64_t chunk_size = 0;
  std::int64_t memory = 0;  // held besides the buffers of what it reads
  double compute = 0.0;
  std::uint32_t name = 0;  // in Runner::task_names_
  bool fsync = false;
  bool direct_io = false;
  GroupRef group;  // its application's memory group, if it has one
};

// An application as its run reads it: its tasks' plans are `tasks` from `first`.
struct AppPlan {
  std::string name;
  Host* host;
  std::uint32_t first;
  std::uint32_t tasks;
};

class Runner {
 public:
  // `owned`: the scenario is the runner's; its applications and files, all the run needs of
  // them planned, are freed before the run starts.
  Runner(const Scenario& scenario, const RunOptions& options, Scenario* owned = nullptr)
      : scenario_(scenario), options_(options), share_(sim_) {
    for (const HostConfig& config : scenario.hosts) {
      auto host = std::make_unique<Host>(
          sim_, share_, HostSpec{config.name, config.cores, config.memory, config.memory_bandwidth, config.cache, config.memory_in_use,
                                   config.page_reporting_delay, config.memory_freed_at_start});
      std::map<std::string, DiskRef> disks;
      for (const DiskSpec& d : config.disks) disks[d.name] = host->add_disk(config.name + ":" + d.name,
                                                                  DiskBandwidth{.read = d.read_bw,
                                                                                .write = d.write_bw,
                                                                                .aggregate_read = d.aggregate_read_bw,
                                                                                .aggregate_write = d.aggregate_write_bw,
                                                                                .request_latency = d.request_latency,
                                                                                .read_ahead = d.read_ahead,
                                                                                .max_request = d.max_request,
                                                                                .write_cache = d.write_cache,
                                                                                .sustained_write = d.sustained_write_bw},
                                                                  d.capacity);  // named as the host's cpu and memory are
      disks_[config.name] = std::move(disks);
      hosts_[config.name] = std::move(host);
      cores_[config.name] = config.cores;
      host_order_.push_back(config.name);
      host_list_.push_back(hosts_[config.name].get());
    }
    std::map<std::string, const Link*> links;
    for (const LinkSpec& l : scenario.links) {
      const Link& link = links_storage_.emplace_back(share_, l.name, l.bandwidth, l.latency, l.sharing);
      links[l.name] = &link;
      if (!l.host_a.empty()) routes_[{l.host_a, l.host_b}] = &routes_storage_.emplace_back(std::vector<const Link*>{&link});
    }
    for (const RouteSpec& r : scenario.routes) {
      std::vector<const Link*> crossed;
      for (const std::string& name : r.links) {
        const auto it = links.find(name);
        if (it == links.end()) throw ConfigError(fmt::format("route from '{}' to '{}': no link named '{}'", r.host_a, r.host_b, name));
        crossed.push_back(it->second);
      }
      routes_[{r.host_a, r.host_b}] = &routes_storage_.emplace_back(std::move(crossed));
    }
    Names names;
    names.files.reserve(scenario.files.size());
    file_order_.reserve(scenario.files.size());
    for (const FileSpec& f : scenario.files) {
      Host& host = host_named(f.host, "file", f.name);
      const auto disk = disks_.at(f.host).find(f.disk);
      if (disk == disks_.at(f.host).end()) throw ConfigError(fmt::format("file '{}': host '{}' has no disk named '{}'", f.name, f.host, f.disk));
      if (!names.files.try_emplace(f.name, static_cast<std::uint32_t>(file_order_.size())).second) {
        throw ConfigError(fmt::format("two files named '{}'", f.name));
      }
      file_order_.push_back({&host, host.add_file(f.name, f.size, disk->second, f.cached)});
    }
    reserve_plans(scenario);
    app_plans_.reserve(scenario.apps.size());
    for (const AppSpec& app : scenario.apps) {
      Host& host = host_named(app.host, "application", app.name);
      // An application with a memory limit is a memory group of its host (a job's cgroup).
      const GroupRef group = app.memory_max > 0 ? host.add_memory_group(app.memory_max, app.memory_high) : GroupRef{};
      app_plans_.push_back({app.name, &host, static_cast<std::uint32_t>(task_plans_.size()), static_cast<std::uint32_t>(app.tasks.size())});
      for (const TaskSpec& task : app.tasks) {
        plan_task(task, names);
        task_plans_.back().group = group;
      }
    }
    first_workflow_plan_ = task_plans_.size();
    // Memory groups are never removed: a run may make at most so many (on one host).
    std::size_t groups = 0;
    for (const AppSpec& app : scenario.apps) groups += app.memory_max > 0 ? 1 : 0;
    for (const WorkflowSpec& w : scenario.workflows) {
      groups += static_cast<std::size_t>(std::count_if(w.tasks.begin(), w.tasks.end(), [](const TaskSpec& t) { return t.memory_limits.max > 0; }));
    }
    if (groups > GroupRef::kMax) {
      throw ConfigError(fmt::format("{} applications and workflow tasks with a memory_max: a run may have at most {} memory groups", groups,
                                    GroupRef::kMax));
    }
    for (const WorkflowSpec& w : scenario.workflows) {
      if (w.hosts.empty()) throw ConfigError(fmt::format("workflow '{}': no host to run on", w.name));
      for (const std::string& h : w.hosts) host_named(h, "workflow", w.name);
      for (const TaskSpec& task : w.tasks) {
        if (!task.host.empty()) host_named(task.host, "task", task.name);
        plan_task(task, names);
      }
    }
    task_names_.shrink_to_fit();
    if (owned != nullptr) {
      // At 10^5 pipelines the specs are a fifth of the run's memory.
      std::vector<AppSpec>().swap(owned->apps);
      std::vector<FileSpec>().swap(owned->files);
    }
  }

  RunResult run() {
    attach_consumers(task_plans_.size());
    const auto wall_start = std::chrono::steady_clock::now();
    for (const AppPlan& app : app_plans_) {
      ++running_;
      sim_.spawn(run_tasks(app.name, {task_plans_.data() + app.first, app.tasks}, *app.host, true));
    }
    const TaskPlan* plan = task_plans_.data() + first_workflow_plan_;
    for (const WorkflowSpec& w : scenario_.workflows) {
      WorkflowHosts& hosts = workflow_hosts_.emplace_back(placement_of(w));
      std::deque<Event>& done = workflow_done_.emplace_back();
      for (std::size_t i = 0; i < w.tasks.size(); ++i) done.emplace_back(sim_);
      std::vector<std::vector<Event*>> prerequisites = prerequisites_of(w, done);
      for (std::size_t i = 0; i < w.tasks.size(); ++i) {
        ++running_;
        sim_.spawn(run_workflow_task(w, w.tasks[i], *plan++, hosts, i, std::move(prerequisites[i]), done[i]));
      }
    }
    if (scenario_.memory_sample_interval > 0.0) {
      sim_.spawn(sample_memory());
    } else {
      // A profile of every change is recorded as the changes happen, from now: the files
      // cached at the start changed memory before there was anything to report to.
      for (std::size_t i = 0; i < host_list_.size(); ++i) {
        host_list_[i]->set_memory_observer([this, i](double now, const MemoryState& m) { record_memory(now, i, m); });
      }
      record_all_memory();
    }

    try {
      std::uint64_t next_progress = 1 << 12;
      while (sim_.step()) {
        // The loader refuses scenarios estimated to run this long; this catches what the
        // estimate missed, before the clock loses its precision.
        if (sim_.now() > options_.max_simulated_time) {
          throw SimulationError(fmt::format("the simulated time passed {:g} s, the most a run may take (RunOptions::max_simulated_time)",
                                            options_.max_simulated_time));
        }
        if (options_.progress && sim_.events_processed() >= next_progress) {
          options_.progress(sim_.now(), sim_.events_processed());
          next_progress += 1 << 12;
        }
      }
    } catch (const SimulationError& e) {
      const std::string what = e.what();
      if (what.rfind("t = ", 0) == 0) throw;
      throw SimulationError(fmt::format("t = {:.6f} s: {}", sim_.now(), what));
    }
    if (running_ != 0) {
      throw SimulationError(fmt::format("t = {:.6f} s: {} task(s) never finished (waiting for each other?)", sim_.now(), running_));
    }
    record_all_memory();
    sink_->on_end(sim_.now());

    RunSummary& s = summary();
    s.end_time = sim_.now();
    for (const PhaseRow& row : recorder_->result().timeline) {
      PhaseTotals& totals = row.phase == PhaseKind::Read ? s.read : row.phase == PhaseKind::Write ? s.write : s.compute;
      totals.seconds += row.end - row.start;
      totals.bytes += row.bytes;
      if (row.phase == PhaseKind::Read) {
        s.disk_read_bytes += row.disk_bytes;
        s.cache_read_bytes += row.cache_bytes;
      }
    }
    for (const auto& [name, host] : hosts_) {
      s.forced_flush_bytes += host->forced_flush_bytes();
      s.periodic_flush_bytes += host->periodic_flush_bytes();
      s.evicted_bytes += host->evicted_bytes();
      s.chunk_operations += host->chunk_operations();
      s.peak_dirty_bytes = std::max(s.peak_dirty_bytes, host->peak_dirty_bytes());
    }
    s.events = sim_.events_processed();
    s.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    s.events_per_second = s.wall_seconds > 0.0 ? static_cast<double>(s.events) / s.wall_seconds : 0.0;
    return std::move(recorder_->result());
  }

 private:
  RunSummary& summary() { return recorder_->result().summary; }

  // The result's recorder, and the run options' consumers beside it: the runner reports to
  // all; the devices and page caches only to the options' consumers, so that with none they
  // report nothing.
  void attach_consumers(std::size_t tasks) {
    const std::string not_recorded = why_cache_contents_not_recorded(tasks);
    record_cache_ = not_recorded.empty();
    recorder_.emplace(3 * tasks, record_cache_ ? 2 * tasks * file_order_.size() : 0, not_recorded);
    std::vector<TraceSink*> all{&*recorder_};
    all.insert(all.end(), options_.consumers.begin(), options_.consumers.end());
    sink_ = all.size() == 1 ? all.front() : &fanouts_.emplace_back(std::move(all));
    const auto one_of = [this](std::vector<TraceSink*> sinks) -> TraceSink* {
      if (sinks.empty()) return nullptr;
      return sinks.size() == 1 ? sinks.front() : &fanouts_.emplace_back(std::move(sinks));
    };
    TraceSink* low = one_of(options_.consumers);
    std::vector<TraceSink*> of_flows;
    std::copy_if(options_.consumers.begin(), options_.consumers.end(), std::back_inserter(of_flows), [](const TraceSink* c) { return c->wants_flows(); });
    share_.set_trace(one_of(std::move(of_flows)));
    for (std::uint32_t i = 0; i < host_list_.size(); ++i) {
      host_list_[i]->set_trace(low, i);
      host_index_.emplace(host_list_[i], i);
    }
    std::vector<std::string> files;
    files.reserve(file_order_.size());
    for (const PlacedFile& f : file_order_) files.push_back(f.host->file_name(f.ref));
    sink_->on_start({.hosts = host_order_, .files = files});
  }

  // Scenarios built in code skip the loader's checks: what the run relies on is checked here.
  // `kind` and `owner` name what asks for the host (e.g. file 'a'), for the error only.
  Host& host_named(const std::string& name, const char* kind, const std::string& owner) const {
    const auto it = hosts_.find(name);
    if (it == hosts_.end()) throw ConfigError(fmt::format("{} '{}': no host named '{}'", kind, owner, name));
    return *it->second;
  }

  // Exact sizes: at 10^5 pipelines a doubling array's spare half would be tens of MB.
  void reserve_plans(const Scenario& scenario) {
    std::size_t tasks = 0;
    std::size_t files = 0;
    const auto count = [&](const std::vector<TaskSpec>& of) {
      tasks += of.size();
      for (const TaskSpec& t : of) files += t.reads.size() + t.writes.size() + t.deletes.size();
    };
    for (const AppSpec& app : scenario.apps) count(app.tasks);
    for (const WorkflowSpec& w : scenario.workflows) count(w.tasks);
    task_plans_.reserve(tasks);
    planned_files_.reserve(files);
  }

  // What planning looks up, by views of the scenario's names: its files (index in file_order_)
  // and the task names met so far (index in task_names_, each name once: a run of pipelines
  // has a few).
  struct Names {
    std::unordered_map<std::string_view, std::uint32_t> files;
    std::unordered_map<std::string_view, std::uint32_t> tasks;
  };

  void plan_task(const TaskSpec& task, Names& names) {
    TaskPlan& plan = task_plans_.emplace_back();
    const auto [known, added] = names.tasks.try_emplace(task.name, static_cast<std::uint32_t>(task_names_.size()));
    if (added) task_names_.push_back(task.name);
    plan.name = known->second;
    const auto add = [&](const std::vector<std::string>& list) {
      for (const std::string& name : list) {
        const auto it = names.files.find(name);
        if (it == names.files.end()) throw ConfigError(fmt::format("task '{}': no file named '{}'", task.name, name));
        planned_files_.push_back(it->second);
      }
      return static_cast<std::uint32_t>(planned_files_.size());
    };
    plan.reads = static_cast<std::uint32_t>(planned_files_.size());
    plan.writes = add(task.reads);
    plan.deletes = add(task.writes);
    plan.end = add(task.deletes);
    plan.chunk_size = task.chunk_size;
    std::int64_t reading = 0;
    for (std::uint32_t f = plan.reads; f < plan.writes; ++f) {
      const PlacedFile& placed = file_order_[planned_files_[f]];
      reading = std::min(reading + placed.host->file_size(placed.ref), units::kMaxBytes * 2);
    }
    plan.memory = std::max<std::int64_t>(0, task.memory - reading);
    plan.compute = task.compute;
    plan.fsync = task.fsync;
    plan.direct_io = task.direct_io;
  }

  // The file of a task's list: `f` in [reads, end) of its plan.
  const PlacedFile& planned(std::uint32_t f) const { return file_order_[planned_files_[f]]; }

  // The file as seen from `client`: its own, or the server's through the link between them
  // (registered once per host and file, when first used).
  FileRef file_on(Host& client, const PlacedFile& stored) {
    if (stored.host == &client) return stored.ref;
    const auto key = std::make_tuple(&client, stored.host, stored.ref.index);
    if (auto it = remote_files_.find(key); it != remote_files_.end()) return it->second;
    const std::string& server = stored.host->name();
    auto route = routes_.find({client.name(), server});
    if (route == routes_.end()) route = routes_.find({server, client.name()});
    if (route == routes_.end()) {
      throw ConfigError(fmt::format("file '{}' is on host '{}', and no route joins it to host '{}'", stored.host->file_name(stored.ref), server,
                                    client.name()));
    }
    const FileRef ref = client.add_remote_file(*stored.host, stored.ref, *route->second);
    remote_files_.emplace(key, ref);
    return ref;
  }

  // The hosts a workflow's tasks may run on, and the scheduler of their cores: the workflow's
  // hosts, then those its tasks name. Each task's candidates are a span of `candidates`.
  struct WorkflowHosts {
    std::vector<Host*> hosts;
    std::unique_ptr<workload::CoreScheduler> cores;
    std::vector<std::size_t> shared;               // the workflow's hosts
    std::vector<std::size_t> own;                  // per task: its own host, if it names one
  };

  WorkflowHosts placement_of(const WorkflowSpec& w) {
    WorkflowHosts p;
    std::vector<int> cores;
    std::map<std::string, std::size_t> index;
    const auto add = [&](const std::string& name) {
      const auto [it, added] = index.try_emplace(name, p.hosts.size());
      if (added) {
        p.hosts.push_back(hosts_.at(name).get());
        cores.push_back(cores_.at(name));
      }
      return it->second;
    };
    for (const std::string& h : w.hosts) p.shared.push_back(add(h));
    int most = 0;  // the most cores of a shared host
    for (const std::size_t h : p.shared) most = std::max(most, cores[h]);
    p.own.reserve(w.tasks.size());
    for (const TaskSpec& t : w.tasks) p.own.push_back(t.host.empty() ? workload::CoreScheduler::kShared : add(t.host));
    for (std::size_t i = 0; i < w.tasks.size(); ++i) {
      const TaskSpec& t = w.tasks[i];
      const bool own = p.own[i] != workload::CoreScheduler::kShared;
      if (t.cores > (own ? cores[p.own[i]] : most)) {
        throw ConfigError(fmt::format("workflow '{}', task '{}': needs {} cores, more than {} has", w.name, t.name, t.cores,
                                      own ? "its host" : "any of its workflow's hosts"));
      }
    }
    p.cores = std::make_unique<workload::CoreScheduler>(sim_, std::move(cores), p.shared);
    return p;
  }

  // A host's row only when its memory differs from its previous row. True if it got one.
  bool record_memory(double now, std::size_t host, const MemoryState& m) {
    if (last_memory_.size() < host_order_.size()) last_memory_.resize(host_order_.size());
    std::optional<MemoryState>& last = last_memory_[host];
    if (last && *last == m) return false;
    last = m;
    sink_->on_memory({.host = static_cast<std::uint32_t>(host), .time = now, .state = m});
    return true;
  }

  bool record_all_memory() {
    bool any = false;
    for (std::size_t i = 0; i < host_list_.size(); ++i) any = record_memory(sim_.now(), i, host_list_[i]->memory()) || any;
    return any;
  }

  // Until some host's memory changes. The hosts are observed only meanwhile, so that a
  // sampled profile does not pay for a call at every change.
  Task<void> wait_for_memory_change() {
    Event changed(sim_);
    for (Host* host : host_list_) {
      host->set_memory_observer([&changed](double, const MemoryState&) {
        if (!changed.triggered()) changed.trigger();
      });
    }
    co_await changed.wait();
    for (Host* host : host_list_) host->set_memory_observer({});
  }

  // A row per host at every tick of memory_sample_interval at which its memory differs from its
  // previous row. Ticks after which nothing changed are skipped, not slept through one by one:
  // the run's events follow its work, not its simulated length (a "1e300 s" compute, or a
  // "1 ns" interval through an idle stretch, took one event per tick for ever).
  Task<void> sample_memory() {
    const double interval = scenario_.memory_sample_interval;
    double tick = sim_.now();
    while (running_ > 0) {
      if (record_all_memory()) {
        tick += interval;
      } else {
        // Nothing changed since the last rows: wait for a change, then go back on the cadence
        // at the first tick at or after it, but not this tick, whose rows were due before it.
        co_await wait_for_memory_change();
        tick += std::max(1.0, std::ceil((sim_.now() - tick) / interval)) * interval;
      }
      co_await sim_.sleep(tick - sim_.now());
    }
  }

  // A row per file after each of the two I/O phases of every task, unless that is too many:
  // empty, or why not.
  std::string why_cache_contents_not_recorded(std::size_t tasks) const {
    const std::size_t phases = 2 * tasks;
    const std::size_t rows = phases * file_order_.size();
    if (!options_.cache_contents) return "switched off";
    if (rows > options_.max_cache_rows) {
      return fmt::format("{} rows ({} I/O phases x {} files) would exceed the limit of {}", rows, phases, file_order_.size(),
                         options_.max_cache_rows);
    }
    return {};
  }

  // A phase that has just ended, with what it moved.
  // What a phase moved: its files' IoResults summed, without their times.
  struct Moved {
    std::int64_t bytes = 0;
    std::int64_t cache_bytes = 0;
    std::int64_t disk_bytes = 0;
  };

  std::uint32_t report_phase(std::string_view app, std::string_view task, const Host& host, PhaseKind kind, double start, const Moved& moved) {
    const std::uint32_t row = phases_++;
    sink_->on_phase({.row = row, .host = host_index_.at(&host), .app = app, .task = task, .kind = kind, .start = start, .end = sim_.now(),
                     .bytes = moved.bytes, .cache_bytes = moved.cache_bytes, .disk_bytes = moved.disk_bytes});
    return row;
  }

  // After the I/O phase of row `phase`.
  void record_cache(std::uint32_t phase) {
    if (!record_cache_) return;
    cached_.resize(file_order_.size());
    for (std::size_t i = 0; i < file_order_.size(); ++i) cached_[i] = file_order_[i].host->cached(file_order_[i].ref);
    sink_->on_cache_contents({.phase_row = phase, .cached = cached_});
  }

  static void add_moved(Moved& sum, const IoResult& r) {
    sum.bytes += r.bytes;
    sum.cache_bytes += r.cache_bytes;
    sum.disk_bytes += r.disk_bytes;
  }

  static Task<IoResult> transfer(Host& host, FileRef file, const TaskPlan& plan, bool reading) {
    return reading ? host.read_file(file, plan.chunk_size, plan.direct_io, plan.group)
                   : host.write_file(file, plan.chunk_size, plan.direct_io, plan.group);
  }

  // Tasks one after the other (an application's, or one workflow task): each holds its memory,
  // reads its inputs whole one after the other, computes, writes its outputs, frees its memory
  // and deletes what it deletes; a phase's row is reported when it ends. One coroutine for all
  // of it: with 10^5 applications in flight every nested frame costs tens of MB (GCC keeps
  // each local of a coroutine in its frame, and frames are recycled per size), so the phases
  // share one loop and one co_await serves reads and writes. `ends_app`: the last task of an
  // application ends it (finish_one).
  static constexpr std::array<PhaseKind, 3> kPhases{PhaseKind::Read, PhaseKind::Compute, PhaseKind::Write};

  Task<void> run_tasks(const std::string& app, std::span<const TaskPlan> plans, Host& host, bool ends_app) {
    for (const TaskPlan& plan : plans) {
      if (plan.memory > 0) co_await host.hold_memory(plan.memory, plan.group);
      std::int64_t read_bytes = 0;
      for (std::uint8_t phase = 0; phase < kPhases.size(); ++phase) {
        const PhaseKind kind = kPhases[phase];
        const double start = sim_.now();
        Moved sum;
        if (kind == PhaseKind::Compute) {
          if (plan.compute > 0.0) co_await host.compute(plan.compute);
        } else {
          const bool reading = kind == PhaseKind::Read;
          for (std::uint32_t f = reading ? plan.reads : plan.writes; f < (reading ? plan.writes : plan.deletes); ++f) {
            if (!deleted_.empty()) note_access(planned_files_[f], reading, app, plan, ends_app);
            const FileRef file = file_on(host, planned(f));
            add_moved(sum, co_await transfer(host, file, plan, reading));
            if (!reading && plan.fsync) co_await host.fsync(file);
          }
          if (reading) read_bytes = sum.bytes;
        }
        const std::uint32_t row = report_phase(app, task_names_[plan.name], host, kind, start, sum);
        if (kind != PhaseKind::Compute) record_cache(row);
      }
      host.release_memory(read_bytes + plan.memory, plan.group);  // the task's memory is freed when it ends
      for (std::uint32_t f = plan.deletes; f < plan.end; ++f) {
        const PlacedFile& stored = planned(f);
        co_await host.delete_file(file_on(host, stored));
        if (stored.host != &host) co_await stored.host->delete_file(stored.ref);  // on the server too
        deleted_.insert_or_assign(planned_files_[f], Deletion{task_names_[plan.name], app, ends_app, sim_.now()});
      }
    }
    if (ends_app) finish_one();
  }

  // A deleted file is gone until a task writes it again: reading it is an error, named with the
  // task that deleted it (the loader refuses the reads whose order the scenario fixes; here are
  // those the run's order decides). `file` is an index into file_order_.
  void note_access(std::uint32_t file, bool reading, std::string_view app, const TaskPlan& plan, bool in_application) {
    const auto it = deleted_.find(file);
    if (it == deleted_.end()) return;
    if (!reading) {
      deleted_.erase(it);
      return;
    }
    const Deletion& d = it->second;
    const auto owner = [](bool application, std::string_view name) { return fmt::format("{} '{}'", application ? "application" : "workflow", name); };
    throw SimulationError(fmt::format("task '{}' of {} reads file '{}', which task '{}' of {} deleted at t = {:.6f} s", task_names_[plan.name],
                                      owner(in_application, app), file_order_[file].host->file_name(file_order_[file].ref), d.task,
                                      owner(d.in_application, d.owner), d.time));
  }

  // What each task of `w` waits for before it starts (`done` holds the ends of its tasks, in
  // workflow order): the tasks named in `after`, then the writers of its inputs in workflow
  // order, a writer once per input it writes (a second wait finds the event triggered and does
  // not suspend). The order is part of the simulation: waiters woken at the same time resume in
  // the order they queued. A map of the workflow's outputs, built once, finds the writers;
  // scanning every task for every input made a workflow quadratic in its tasks.
  static std::vector<std::vector<Event*>> prerequisites_of(const WorkflowSpec& w, std::deque<Event>& done) {
    std::unordered_map<std::string, std::size_t> task_index;
    std::unordered_map<std::string, std::vector<std::size_t>> writers;  // one per file in a loaded scenario
    for (std::size_t i = 0; i < w.tasks.size(); ++i) {
      if (!task_index.emplace(w.tasks[i].name, i).second) {
        throw ConfigError(fmt::format("workflow '{}': two tasks named '{}'", w.name, w.tasks[i].name));
      }
      for (const std::string& file : w.tasks[i].writes) {
        std::vector<std::size_t>& of_file = writers[file];
        if (of_file.empty() || of_file.back() != i) of_file.push_back(i);  // a file listed twice is one output
      }
    }
    std::vector<std::vector<Event*>> waits(w.tasks.size());
    for (std::size_t i = 0; i < w.tasks.size(); ++i) {
      const TaskSpec& task = w.tasks[i];
      for (const std::string& before : task.after) {
        const auto it = task_index.find(before);
        if (it == task_index.end()) {
          throw ConfigError(fmt::format("workflow '{}': task '{}' comes after an unknown task '{}'", w.name, task.name, before));
        }
        waits[i].push_back(&done[it->second]);
      }
      std::vector<std::size_t> producers;
      for (const std::string& input : task.reads) {
        if (auto it = writers.find(input); it != writers.end()) producers.insert(producers.end(), it->second.begin(), it->second.end());
      }
      std::sort(producers.begin(), producers.end());  // workflow order
      for (std::size_t p : producers) waits[i].push_back(&done[p]);
    }
    return waits;
  }

  Task<void> run_workflow_task(const WorkflowSpec& w, const TaskSpec& task, const TaskPlan& plan, WorkflowHosts& hosts, std::size_t index,
                               std::vector<Event*> prerequisites, Event& done) {
    for (Event* prerequisite : prerequisites) co_await prerequisite->wait();
    const std::size_t host = co_await hosts.cores->acquire(hosts.own[index], task.cores);
    if (task.memory_limits.max > 0) {
      // Its own memory group, on the host it got (a pod's or job's cgroup).
      TaskPlan in_group = plan;
      in_group.group = hosts.hosts[host]->add_memory_group(task.memory_limits.max, task.memory_limits.high);
      co_await run_tasks(w.name, {&in_group, 1}, *hosts.hosts[host], false);
    } else {
      co_await run_tasks(w.name, {&plan, 1}, *hosts.hosts[host], false);
    }
    hosts.cores->release(host, task.cores);
    done.trigger();
    finish_one();
  }

  void finish_one() {
    --running_;
    if (running_ == 0) summary().makespan = sim_.now();
  }

  const Scenario& scenario_;
  const RunOptions& options_;
  Simulator sim_;
  FairShare share_;
  std::map<std::string, std::unique_ptr<Host>> hosts_;
  std::map<std::string, int> cores_;
  std::map<std::string, std::map<std::string, DiskRef>> disks_;
  std::vector<std::string> host_order_;
  std::vector<Host*> host_list_;                      // in host_order_
  std::vector<std::optional<MemoryState>> last_memory_;  // per host, its last memory row
  std::deque<Link> links_storage_;
  std::deque<Route> routes_storage_;
  std::map<std::pair<std::string, std::string>, const Route*> routes_;
  std::vector<AppPlan> app_plans_;    // per application, in order
  std::vector<TaskPlan> task_plans_;  // per task, apps' then workflows', in order
  std::size_t first_workflow_plan_ = 0;
  std::vector<std::string> task_names_;  // what TaskPlan::name names
  std::vector<std::uint32_t> planned_files_;  // the files of the tasks' lists, in file_order_
  std::map<std::tuple<const Host*, const Host*, std::uint32_t>, FileRef> remote_files_;  // (client, server, server's file)
  std::vector<PlacedFile> file_order_;  // the scenario's files, in its order
  // The files deleted and not written since, by index in file_order_, and who deleted them.
  struct Deletion {
    std::string task;
    std::string owner;  // its application or workflow
    bool in_application;
    double time;
  };
  std::unordered_map<std::uint32_t, Deletion> deleted_;
  bool record_cache_ = false;
  std::deque<WorkflowHosts> workflow_hosts_;  // per workflow
  std::deque<std::deque<Event>> workflow_done_;  // per workflow, its tasks' ends in workflow order
  int running_ = 0;
  std::optional<workload::ResultRecorder> recorder_;
  std::deque<workload::TraceFanout> fanouts_;
  TraceSink* sink_ = nullptr;                        // what the runner reports to: the recorder, and the consumers
  std::unordered_map<const Host*, std::uint32_t> host_index_;  // in host_order_
  std::uint32_t phases_ = 0;                         // ended so far
  std::vector<std::int64_t> cached_;                 // per file, after a phase: record_cache's buffer
};

}  // namespace

RunResult run_scenario(const Scenario& scenario, const RunOptions& options) {
  Runner runner(scenario, options);
  return runner.run();
}

RunResult run_scenario(Scenario&& scenario, const RunOptions& options) {
  Scenario owned = std::move(scenario);
  Runner runner(owned, options, &owned);
  return runner.run();
}

}  // namespace pagecache
