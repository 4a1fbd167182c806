// run_scenario: builds the platform of a resolved scenario, runs its applications and
// workflows to the end, and collects the timeline, the memory profile and the cache contents.

#include "workload/runner.hpp"

#include <pagecache/error.hpp>

#include <pagecache/units.hpp>

#include <fmt/format.h>

#include <functional>

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <utility>

namespace pagecache {

namespace workload {

namespace {

// What each task of `w` waits for before it starts (`done` holds the ends of its tasks, in
// workflow order): the tasks named in `after`, then the writers of its inputs in workflow
// order, a writer once per input it writes (a second wait finds the event triggered and does
// not suspend). The order is part of the simulation: waiters woken at the same time resume in
// the order they queued. A map of the workflow's outputs, built once, finds the writers;
// scanning every task for every input made a workflow quadratic in its tasks.
std::vector<std::vector<Event*>> prerequisites_of(const WorkflowSpec& w, std::deque<Event>& done) {
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

Task<IoResult> transfer(Host& host, FileRef file, const PreparedTask& plan, Thread thread, bool reading) {
  return reading ? host.read_file(file, plan.chunk_size, plan.direct_io, thread)
                 : host.write_file(file, plan.chunk_size, plan.direct_io, thread);
}

constexpr std::array<PhaseKind, 3> kPhases{PhaseKind::Read, PhaseKind::Compute, PhaseKind::Write};

// POSIX_FADV_DONTNEED over what `requests` cover: the region, or each range.
void drop_region(Host& host, FileRef file, const RequestPattern& requests) {
  if (requests.kind != RequestPattern::Kind::Ranges) {
    host.dont_need(file, ByteRange{.offset = requests.offset, .length = requests.length});
    return;
  }
  for (const ByteRange& range : requests.ranges) host.dont_need(file, range);
}

}  // namespace

Runner::Runner(const Scenario& scenario, const RunOptions& options, Scenario* owned) : Runner(scenario, options, owned, FileIndex{}) {}

Runner::Runner(const Scenario& scenario, const RunOptions& options, Scenario* owned, FileIndex&& files)
    : scenario_(scenario),
      options_(options),
      share_(sim_),
      platform_(sim_, share_, scenario, files),
      prepared_(scenario, platform_, files),
      memory_(sim_, platform_.hosts(), scenario.memory_sample_interval),
      deleted_(platform_) {
  if (owned != nullptr) {
    // Not needed once planned, and at 10^5 pipelines a large share of the run's memory.
    std::vector<AppSpec>().swap(owned->apps);
    std::vector<FileSpec>().swap(owned->files);
  }
}

RunResult Runner::run() {
  trace_.emplace(options_, share_, platform_, prepared_.timeline_rows(), prepared_.io_phases());
  const auto wall_start = std::chrono::steady_clock::now();
  start_applications();
  start_workflows();
  memory_.start(trace_->sink(), running_);
  simulate();
  if (running_ != 0) {
    throw SimulationError(fmt::format("t = {} s: {} task(s) never finished (waiting for each other?)", units::format_instant(sim_.now()), running_));
  }
  memory_.record_all();
  trace_->sink().on_end(sim_.now());
  summarize(wall_start);
  return std::move(trace_->result());
}

void Runner::start_applications() {
  const std::vector<PreparedApp>& apps = prepared_.apps();
  const std::vector<AppWait>& waits = prepared_.app_waits();
  if (!waits.empty()) {
    for (std::size_t i = 0; i < apps.size(); ++i) app_done_.emplace_back(sim_);
  }
  auto wait = waits.begin();
  for (std::size_t i = 0; i < apps.size(); ++i) {
    ++running_;
    if (waits.empty()) {
      sim_.spawn(run_tasks(apps[i].name, prepared_.tasks_of(apps[i]), *apps[i].host, true));
      continue;
    }
    std::vector<Event*> before;
    if (wait != waits.end() && wait->app == i) {
      for (const std::uint32_t a : wait->after) before.push_back(&app_done_[a]);
      ++wait;
    }
    sim_.spawn(run_app_in_order(i, std::move(before)));
  }
}

Task<void> Runner::run_app_in_order(std::size_t index, std::vector<Event*> before) {
  for (Event* event : before) co_await event->wait();
  const PreparedApp& app = prepared_.apps()[index];
  co_await run_tasks(app.name, prepared_.tasks_of(app), *app.host, true);
  app_done_[index].trigger();
}

void Runner::start_workflows() {
  const PreparedTask* plan = prepared_.workflow_tasks();
  for (const WorkflowSpec& w : scenario_.workflows) {
    WorkflowHosts& hosts = workflow_hosts_.emplace_back(place_workflow(w, platform_, sim_));
    std::deque<Event>& done = workflow_done_.emplace_back();
    for (std::size_t i = 0; i < w.tasks.size(); ++i) done.emplace_back(sim_);
    std::vector<std::vector<Event*>> prerequisites = prerequisites_of(w, done);
    for (std::size_t i = 0; i < w.tasks.size(); ++i) {
      ++running_;
      sim_.spawn(run_workflow_task(w, w.tasks[i], *plan++, hosts, i, std::move(prerequisites[i]), done[i]));
    }
  }
}

// Every event to the last; an error names the simulated time it happened at.
void Runner::simulate() {
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
    throw SimulationError(fmt::format("t = {} s: {}", units::format_instant(sim_.now()), what));
  }
}

void Runner::summarize(std::chrono::steady_clock::time_point wall_start) {
  RunSummary& s = trace_->result().summary;
  s.end_time = sim_.now();
  for (const PhaseRow& row : trace_->result().timeline) {
    PhaseTotals& totals = row.phase == PhaseKind::Read ? s.read : row.phase == PhaseKind::Write ? s.write : s.compute;
    totals.seconds += row.end - row.start;
    totals.bytes += row.bytes;
    if (row.phase == PhaseKind::Read) {
      s.disk_read_bytes += row.disk_bytes;
      s.cache_read_bytes += row.cache_bytes;
    }
  }
  for (const Host* host : platform_.hosts()) {
    s.forced_flush_bytes += host->forced_flush_bytes();
    s.periodic_flush_bytes += host->periodic_flush_bytes();
    s.evicted_bytes += host->evicted_bytes();
    s.chunk_operations += host->chunk_operations();
    s.peak_dirty_bytes = std::max(s.peak_dirty_bytes, host->peak_dirty_bytes());
  }
  s.events = sim_.events_processed();
  s.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  s.events_per_second = s.wall_seconds > 0.0 ? static_cast<double>(s.events) / s.wall_seconds : 0.0;
}

// Tasks one after the other (an application's, or one workflow task): each holds its memory,
// reads its inputs whole one after the other, computes, writes its outputs, frees its memory
// and deletes what it deletes; a phase's row is reported when it ends. One coroutine for all
// of it: with 10^5 applications in flight every nested frame costs tens of MB (GCC keeps
// each local of a coroutine in its frame, and frames are recycled per size), so the phases
// share one loop and one co_await serves reads and writes. `ends_app`: the last task of an
// application ends it (finish_one).
Task<void> Runner::run_tasks(const std::string& app, std::span<const PreparedTask> plans, Host& host, bool ends_app) {
  for (const PreparedTask& plan : plans) {
    const Thread thread = host.start_thread(plan.group);
    if (plan.memory > 0) co_await host.hold_memory(plan.memory, thread);
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
          if (!deleted_.empty()) deleted_.note_access(prepared_.file(f), reading, app, prepared_.task_name(plan), ends_app);
          const FileRef file = platform_.file_on(host, task_file(f));
          add_moved(sum, co_await transfer(host, file, plan, thread, reading));
          if (!reading && plan.fsync) co_await host.fsync(file);
        }
        if (reading) read_bytes = sum.bytes;
      }
      const std::uint32_t row = trace_->report_phase(app, prepared_.task_name(plan), host, kind, start, sim_.now(), sum);
      if (kind != PhaseKind::Compute) trace_->record_cache(row);
      if (kind == PhaseKind::Read && plan.accesses != plan.accesses_end) co_await run_accesses(app, plan, host, thread, ends_app);
    }
    host.release_memory(read_bytes + plan.memory, thread);  // the task's memory is freed when it ends
    host.end_thread(thread);
    for (std::uint32_t f = plan.deletes; f < plan.end; ++f) {
      const PlacedFile& stored = task_file(f);
      co_await host.delete_file(platform_.file_on(host, stored));
      if (stored.host != &host) co_await stored.host->delete_file(stored.ref);  // on the server too
      deleted_.note_deleted(prepared_.file(f), app, prepared_.task_name(plan), ends_app, sim_.now());
    }
  }
  if (ends_app) finish_one();
}

// A task's accesses, after its reads, in order. A frame of its own, made only for the tasks
// that have accesses.
Task<void> Runner::run_accesses(const std::string& app, const PreparedTask& plan, Host& host, Thread thread, bool ends_app) {
  for (std::uint32_t a = plan.accesses; a < plan.accesses_end; ++a) {
    const PreparedAccess& access = prepared_.access(a);
    if (access.of_file) co_await access_file(app, plan, access, host, thread, ends_app);
    else co_await read_file_set(app, plan, access, host, thread);
  }
}

// Each epoch reads its files whole, one after the other, freeing each file's buffer once read,
// and is reported as a read row of its own, its task named "TASK:SET[epoch N]".
Task<void> Runner::read_file_set(const std::string& app, const PreparedTask& plan, const PreparedAccess& access, Host& host, Thread thread) {
  SampleOrder order(access.set.count, access.order, access.seed);
  for (std::int64_t epoch = 1; epoch <= access.repeat; ++epoch) {
    const double start = sim_.now();
    Moved sum;
    order.start_epoch();
    for (std::int64_t i = 0; i < access.count; ++i) {
      const PlacedFile& stored = platform_.files()[access.set.first + order.next()];
      const IoResult read = co_await host.read_file(platform_.file_on(host, stored), plan.chunk_size, plan.direct_io, thread);
      host.release_memory(read.bytes, thread);  // a data loader keeps no sample
      add_moved(sum, read);
    }
    const std::string label = fmt::format("{}:{}[epoch {}]", prepared_.task_name(plan), prepared_.set_name(access), epoch);
    trace_->record_cache(trace_->report_phase(app, label, host, PhaseKind::Read, start, sim_.now(), sum));
  }
}

// Each epoch one read_ranges or write_ranges of the pattern's requests (the read holds a
// request's buffer while it runs), reported as a read or write row, "TASK:FILE[epoch N]".
Task<void> Runner::access_file(const std::string& app, const PreparedTask& plan, const PreparedAccess& access, Host& host, Thread thread, bool ends_app) {
  const PlacedFile& stored = platform_.files()[access.file];
  const std::string& name = stored.host->file_name(stored.ref);
  // The loader refuses these; a scenario built in code is told here.
  if (stored.host != &host) {
    throw ConfigError(fmt::format("task '{}': file '{}' is on host '{}': accesses by part are of files of the task's host ('{}') only",
                                  prepared_.task_name(plan), name, stored.host->name(), host.name()));
  }
  RequestStream stream(access.requests);
  // fio's runtime: checked before each request, over all epochs.
  const double deadline = access.runtime > 0.0 ? sim_.now() + access.runtime : std::numeric_limits<double>::infinity();
  std::function<bool(ByteRange&)> next = [&stream, this, deadline](ByteRange& r) { return sim_.now() < deadline && stream.next(r); };
  for (std::int64_t epoch = 1; epoch <= access.repeat && sim_.now() < deadline; ++epoch) {
    if (!deleted_.empty()) deleted_.note_access(access.file, !access.writing, app, prepared_.task_name(plan), ends_app);
    if (access.invalidate) drop_region(host, stored.ref, access.requests);
    const double start = sim_.now();
    stream.start_epoch(access.reshuffle ? epoch - 1 : 0);
    Moved sum;
    if (access.writing) {
      add_moved(sum, co_await host.write_ranges(stored.ref, next, thread, plan.direct_io));
      if (plan.fsync) co_await host.fsync(stored.ref);
    } else {
      add_moved(sum, co_await host.read_ranges(stored.ref, next, access.requests.request, thread, access.advice, plan.direct_io));
    }
    if (access.drop_after) drop_region(host, stored.ref, access.requests);
    const std::string label = fmt::format("{}:{}[epoch {}]", prepared_.task_name(plan), name, epoch);
    const PhaseKind kind = access.writing ? PhaseKind::Write : PhaseKind::Read;
    trace_->record_cache(trace_->report_phase(app, label, host, kind, start, sim_.now(), sum));
  }
}

Task<void> Runner::run_workflow_task(const WorkflowSpec& w, const TaskSpec& task, const PreparedTask& plan, WorkflowHosts& hosts, std::size_t index,
                                     std::vector<Event*> prerequisites, Event& done) {
  for (Event* prerequisite : prerequisites) co_await prerequisite->wait();
  const std::size_t host = co_await hosts.cores->acquire(hosts.own[index], task.cores);
  if (task.memory_limits.max > 0) {
    // Its own memory group, on the host it got (a pod's or job's cgroup).
    PreparedTask in_group = plan;
    in_group.group = hosts.hosts[host]->add_memory_group(task.memory_limits.max, task.memory_limits.high);
    co_await run_tasks(w.name, {&in_group, 1}, *hosts.hosts[host], false);
  } else {
    co_await run_tasks(w.name, {&plan, 1}, *hosts.hosts[host], false);
  }
  hosts.cores->release(host, task.cores);
  done.trigger();
  finish_one();
}

void Runner::finish_one() {
  --running_;
  if (running_ == 0) trace_->result().summary.makespan = sim_.now();
}

}  // namespace workload

RunResult run_scenario(const Scenario& scenario, const RunOptions& options) {
  workload::Runner runner(scenario, options);
  return runner.run();
}

RunResult run_scenario(Scenario&& scenario, const RunOptions& options) {
  Scenario owned = std::move(scenario);
  workload::Runner runner(owned, options, &owned);
  return runner.run();
}

}  // namespace pagecache
