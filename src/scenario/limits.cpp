#include "scenario/limits.hpp"
#include "estimate/estimate.hpp"

#include <pagecache/units.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cstddef>
#include <optional>
#include <limits>
#include <string_view>
#include <utility>

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

using namespace estimate;  // the pre-run estimate the limits check

std::string limits_hint(const ScenarioLimits& limits) {
  const ScenarioLimits forced = ScenarioLimits::forced();
  const bool below = limits.max_tasks < forced.max_tasks || limits.max_files < forced.max_files || limits.max_hosts < forced.max_hosts ||
                     limits.max_events < forced.max_events ||
                     limits.max_simulated_time < forced.max_simulated_time || limits.max_memory_rows < forced.max_memory_rows;
  return below ? " without --force" : "";
}

namespace {

// The key setting a task's chunk size, where it is written: the task's own, else its
// application's or workflow's, else (the default) the task's table.
std::pair<const Origin*, const char*> chunk_key(const Origin& task, const Origin& owner) {
  if (task.has("chunk_size")) return {&task, "chunk_size"};
  if (owner.has("chunk_size")) return {&owner, "chunk_size"};
  return {&task, "chunk_size"};
}

// A task's access (its [[...access]] table number `i`), where it is written; the task's table
// for a task not read from TOML.
Origin access_origin(const Origin& task, std::size_t i) {
  const toml::array* list = task.table != nullptr ? task.table->get_as<toml::array>("access") : nullptr;
  if (list == nullptr || i >= list->size() || !list->get(i)->is_table()) return task;
  return Origin{list->get(i)->as_table(), fmt::format("{}.access[{}]", task.path, i), task.file};
}

const Origin& task_origin(const Origins& o, const TaskAt& t) {
  return t.workflow ? o.workflow_tasks[t.owner][t.task] : o.app_task(t.owner, t.task);
}

// Files, file sets' included (read_file_sets checked each set as it came, against those before).
void check_files(const Scenario& s, const Origins& o, const ScenarioLimits& limits) {
  double files = static_cast<double>(s.files.size());
  for (const FileSetSpec& set : s.file_sets) files += static_cast<double>(set.count);
  if (files <= static_cast<double>(limits.max_files)) return;
  const std::string message = fmt::format("{:.0f} files, more than the {} a run may have{}", files, limits.max_files, limits_hint(limits));
  // Most likely a file set's count: blame the largest.
  const auto set = std::max_element(s.file_sets.begin(), s.file_sets.end(), [](const FileSetSpec& a, const FileSetSpec& b) { return a.count < b.count; });
  if (set != s.file_sets.end() && static_cast<double>(set->count) > files / 2) {
    o.file_sets[static_cast<std::size_t>(set - s.file_sets.begin())].fail("count", message);
  }
  o.root.fail_table(message);
}

// Timeline rows, held in memory until written: three per task, and an access's one per epoch,
// blamed on the access with the most.
void check_timeline_rows(const Scenario& s, const Origins& o, const ScenarioLimits& limits, std::size_t tasks) {
  double rows = 3.0 * static_cast<double>(tasks), most = 0.0;
  std::optional<std::pair<TaskAt, std::size_t>> blamed;
  const auto note = [&](const std::vector<TaskSpec>& of, bool workflow, std::size_t owner) {
    for (std::size_t t = 0; t < of.size(); ++t) {
      for (std::size_t i = 0; i < of[t].accesses.size(); ++i) {
        const double epochs = static_cast<double>(of[t].accesses[i].repeat);
        rows += epochs;
        if (epochs > most) {
          most = epochs;
          blamed = {TaskAt{workflow, owner, t}, i};
        }
      }
    }
  };
  for (std::size_t a = 0; a < s.apps.size(); ++a) note(s.apps[a].tasks, false, a);
  for (std::size_t w = 0; w < s.workflows.size(); ++w) note(s.workflows[w].tasks, true, w);
  if (rows <= 3.0 * static_cast<double>(limits.max_tasks) || !blamed) return;
  access_origin(task_origin(o, blamed->first), blamed->second)
      .fail("repeat", fmt::format("the timeline would hold {:.3g} rows (three per task, one per access and epoch), more than the {} a run may "
                                  "have{}",
                                  rows, 3 * limits.max_tasks, limits_hint(limits)));
}

// Too many events, most of them for an access's epochs over a file set: its count and repeat
// make them.
[[noreturn]] void fail_epochs(const Origin& access, const RunEstimate& e, const ScenarioLimits& limits) {
  // Of one file, the requests per epoch are the count, else the region over the request size.
  const char* key = access.has("file") && !access.has("count") && !access.has("repeat") ? "request"
                    : access.has("repeat") || !access.has("count")                     ? "repeat"
                                                                                        : "count";
  access.fail(key,
              fmt::format("the run would take about {:.3g} events, {:.3g} of them for {:.3g} chunk operations (each file's bytes over its "
                          "task's chunk size, for every read and write, and every file or request of an access in each epoch), more "
                          "than the {:.3g} a run may take{}: fewer epochs, or files or requests per epoch, make fewer",
                          e.events(), e.transfer_events, e.chunk_operations, limits.max_events, limits_hint(limits)));
}

// The key that sets the longest stretch, where it is written.
std::pair<const Origin*, const char*> stretch_key(const Stretch& s, const Origins& o) {
  switch (s.kind) {
    case Stretch::Kind::Disk:
      return {&o.disks[s.index][s.disk], s.reading ? "read_bw" : "write_bw"};
    case Stretch::Kind::Memory: {
      const Origin& host = o.hosts[s.index];
      if (s.reading) return {&host, host.has("memory_aggregate_read_bw") ? "memory_aggregate_read_bw" : "memory_read_bw"};
      return {&host, host.has("memory_aggregate_write_bw") ? "memory_aggregate_write_bw" : "memory_write_bw"};
    }
    case Stretch::Kind::Cores:
      return {&o.hosts[s.index], "cores"};
    case Stretch::Kind::Link:
      return {&o.links[s.index], "bandwidth"};
    case Stretch::Kind::Application:
      if (s.latency) return {&o.links[s.link], "latency"};
      return {&o.app_task(s.index, s.task), o.from_pipelines(s.index) ? "cpu_time" : "compute"};
    case Stretch::Kind::Workflow:
      if (s.latency) return {&o.links[s.link], "latency"};
      return {&o.workflow_tasks[s.index][s.task], "compute"};
    case Stretch::Kind::None:
      break;
  }
  return {&o.root, "title"};  // nothing takes any time: never refused
}

// A [hosts.page_cache] key, for a host whose origin may be its page_cache table or, without
// one, the host's own.
std::string page_cache_key(const Origin& page_cache, const std::string& key) {
  const std::string_view path = page_cache.path;
  return path.size() >= 10 && path.substr(path.size() - 10) == "page_cache" ? key : "page_cache." + key;
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
  check_files(s, o, limits);
  if (static_cast<double>(s.hosts.size()) > static_cast<double>(limits.max_hosts)) {
    // Most likely a host group's count: blame it.
    const auto group = std::find_if(o.host_groups.begin(), o.host_groups.end(),
                                    [&](const auto& g) { return static_cast<double>(g.second.second) > static_cast<double>(limits.max_hosts) / 2; });
    const std::string message = fmt::format("{} hosts, more than the {} a run may have{}", s.hosts.size(), limits.max_hosts, hint);
    if (group != o.host_groups.end()) o.hosts[group->second.first].fail("count", message);
    o.root.fail_table(message);
  }

  check_timeline_rows(s, o, limits, tasks);

  const RunEstimate e = estimate_run(s);
  const double simulated = e.longest.seconds;
  if (simulated > limits.max_simulated_time) {
    const auto [origin, key] = stretch_key(e.longest, o);
    origin->fail(key, fmt::format("the run would take at least about {:.3g} s of simulated time ({}), more than the {:g} s "
                                  "a run may take{}",
                                  simulated, e.longest.what, limits.max_simulated_time, hint));
  }

  // Events, blamed on their largest source.
  const double events = e.events();
  if (events > limits.max_events) {
    const double largest = std::max({e.transfer_events, e.throttle_events, e.flusher_events, e.sampler_events});
    if (largest == e.transfer_events) {
      const TaskAt& t = e.most_operations;
      if (e.most_operations_access) fail_epochs(access_origin(task_origin(o, t), *e.most_operations_access), e, limits);
      const auto [origin, key] = t.workflow ? chunk_key(o.workflow_tasks[t.owner][t.task], o.workflows[t.owner])
                                            : chunk_key(o.app_task(t.owner, t.task), o.app(t.owner));
      origin->fail(key, fmt::format("the run would take about {:.3g} events, {:.3g} of them for {:.3g} chunk operations (each file's "
                                    "bytes over its task's chunk size, for every read and write), more than the {:.3g} a run may "
                                    "take{}: a larger chunk_size makes fewer",
                                    events, e.transfer_events, e.chunk_operations, limits.max_events, hint));
    }
    if (largest == e.throttle_events) {
      const std::size_t h = e.most_throttled_host;
      o.page_caches[h].fail(page_cache_key(o.page_caches[h], "dirty_throttling"),
                            fmt::format("the writers of host '{}' would pause about {:.3g} times (dirty throttling: each throttled "
                                        "writer waits for the disk a second at a time), and the run would take about {:.3g} events, "
                                        "more than the {:.3g} a run may take{}: fewer writers at once, more memory or a faster disk make "
                                        "fewer",
                                        s.hosts[h].name, e.most_throttled_pauses, events, limits.max_events, hint));
    }
    if (largest == e.flusher_events) {
      const std::size_t h = e.busiest_flusher;
      o.page_caches[h].fail(page_cache_key(o.page_caches[h], "writeback_interval"),
                            fmt::format("the flusher of host '{}' would wake about {:.3g} times while it has dirty data, and the run "
                                        "would take about {:.3g} events, more than the {:.3g} a run may take{}",
                                        s.hosts[h].name, e.busiest_flusher_wakeups, events, limits.max_events, hint));
    }
    o.root.fail("memory_sample_interval",
                fmt::format("the memory sampler would wake about {:.3g} times, and the run would take about {:.3g} events, more than "
                            "the {:.3g} a run may take{}: a longer interval makes fewer",
                            e.sampler_events, events, limits.max_events, hint));
  }

  // memory.csv: a row per host at most at every change (a few per chunk operation).
  const double rows = e.memory_rows;
  const double interval = s.memory_sample_interval;
  if (rows > limits.max_memory_rows) {
    o.root.fail("memory_sample_interval",
                fmt::format("memory.csv would hold about {:.3g} rows ({}), more than the {:.3g} a run may write{}: a longer interval "
                            "makes fewer",
                            rows, interval > 0.0 ? fmt::format("a row per host every {:g} s over {:.3g} s", interval, simulated) : "a row at every change",
                            limits.max_memory_rows, hint));
  }
}

}  // namespace pagecache::scenario
