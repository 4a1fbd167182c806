// The applications of a scenario: [pipelines] (N identical pipelines, expanded into
// applications and files) and [[apps]] with their [[apps.tasks]]; and what the tasks of
// applications and workflows share: a task's keys and a memory group's limits.

#include "scenario/loader_sections.hpp"

#include "scenario/limits.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>

namespace pagecache::scenario {

MemoryLimits read_memory_limits(TomlReader& r, const char* whose, MemoryLimits inherited) {
  MemoryLimits m = r.has("memory_max") ? MemoryLimits{} : inherited;
  m.max = r.optional_size("memory_max").value_or(m.max);
  if (r.has("memory_max") && m.max <= 0) r.fail("memory_max", fmt::format("must be > 0 ({} memory group's limit)", whose));
  m.high = r.optional_size("memory_high").value_or(m.high);
  if (r.has("memory_high") && (m.high <= 0 || m.max == 0 || m.high > m.max)) {
    r.fail("memory_high", "must be > 0 and at most memory_max, which it needs");
  }
  return m;
}

TaskSpec read_task(const toml::table& table, std::string path, std::size_t index, std::int64_t default_chunk, const std::string& file,
                   AccessTargets& targets, bool in_workflow, MemoryLimits workflow_limits) {
  TomlReader r(table, std::move(path), file);
  TaskSpec t;
  t.name = r.name("name", std::to_string(index + 1));
  if (in_workflow) {
    t.host = r.name("host", "");
    t.cores = static_cast<int>(r.optional_integer("cores", 1, 1'000'000).value_or(1));
  }
  t.memory = r.optional_size("memory").value_or(0);
  t.reads = r.names("read");
  t.chunk_size = r.optional_size("chunk_size").value_or(default_chunk);  // an access's default request
  if (t.chunk_size <= 0) r.fail("chunk_size", "must be > 0");
  t.accesses = read_accesses(r, targets, t.chunk_size);
  t.compute = r.optional_duration("compute").value_or(0.0);
  t.writes = r.names("write");
  if (in_workflow) {
    t.after = r.names("after");
    t.memory_limits = read_memory_limits(r, "the task's", workflow_limits);
  }
  t.fsync = r.optional_bool("fsync").value_or(false);
  t.direct_io = r.optional_bool("direct_io").value_or(false);
  if (t.direct_io && std::any_of(t.accesses.begin(), t.accesses.end(), [](const AccessSpec& a) { return !a.file.empty() && a.mode == AccessMode::Append; })) {
    r.fail("direct_io", "appends (mode = \"append\") through O_DIRECT are not modelled yet");
  }
  t.deletes = r.names("delete");
  r.finish();
  return t;
}

namespace {

// [pipelines]: N identical concurrent pipelines of T tasks; task k of pipeline i reads
// file k and writes file k+1 of that pipeline ("file_k" when N = 1, else "p<i>_file_k").
void expand_pipelines(const toml::table& table, Scenario& s, const std::string& file, const ScenarioLimits& limits,
                      Origins& origins) {
  TomlReader r(table, "pipelines", file);
  origins.pipelines = Origin{&table, "pipelines", &file};
  const std::int64_t count = r.optional_integer("count").value_or(1);
  if (count < 1) r.fail("count", "must be >= 1");
  const std::string host = r.name("host", s.hosts.empty() ? std::string() : s.hosts.front().name);
  const std::string files_host = r.name("files_host", host);
  std::string disk = r.name("disk", "");
  const std::int64_t size = r.required_size("file_size");
  const std::int64_t tasks = r.optional_integer("tasks").value_or(3);
  if (tasks < 1) r.fail("tasks", "must be >= 1");
  // Checked before anything is made: a count of 10^9 would otherwise fill the memory first.
  // Doubles, so that the products cannot overflow.
  const double task_total = static_cast<double>(count) * static_cast<double>(tasks) + static_cast<double>(s.apps.size());
  const double file_total = static_cast<double>(count) * (static_cast<double>(tasks) + 1.0) + static_cast<double>(s.files.size());
  const char* culprit = tasks > count ? "tasks" : "count";
  if (task_total > static_cast<double>(limits.max_tasks)) {
    r.fail(culprit, fmt::format("{} pipelines of {} tasks are {:.3g} tasks, more than the {} a run may have{}", count, tasks, task_total,
                                limits.max_tasks, limits_hint(limits)));
  }
  if (file_total > static_cast<double>(limits.max_files)) {
    r.fail(culprit, fmt::format("{} pipelines of {} tasks use {:.3g} files, more than the {} a run may have{}", count, tasks, file_total,
                                limits.max_files, limits_hint(limits)));
  }
  const double cpu = r.optional_duration("cpu_time").value_or(0.0);
  const std::int64_t chunk = r.optional_size("chunk_size").value_or(100'000'000);
  if (chunk <= 0) r.fail("chunk_size", "must be > 0");
  const bool cached = r.optional_bool("inputs_cached").value_or(false);
  const MemoryLimits memory_limits = read_memory_limits(r, "a pipeline's");
  r.finish();
  // A host group: the pipelines spread over its members in blocks (pipeline i on member
  // ceil(i * members / count)), each member's page cache its own.
  const auto group = origins.host_groups.find(host);
  if (group == origins.host_groups.end() && std::none_of(s.hosts.begin(), s.hosts.end(), [&](const HostConfig& c) { return c.name == host; })) {
    r.fail("host", fmt::format("no host named '{}'", host));
  }
  const auto host_of = [&](std::int64_t i) -> const std::string& {
    if (group == origins.host_groups.end()) return host;
    const auto [first, members] = group->second;
    return s.hosts[first + static_cast<std::size_t>((i - 1) * static_cast<std::int64_t>(members) / count)].name;
  };
  if (origins.host_groups.count(files_host) != 0) {
    r.fail(r.has("files_host") ? "files_host" : "host",
           fmt::format("'{}' is a host group: the pipelines' files are on one host (files_host = \"...\")", files_host));
  }
  const auto h = std::find_if(s.hosts.begin(), s.hosts.end(), [&](const HostConfig& c) { return c.name == files_host; });
  if (h == s.hosts.end()) r.fail("files_host", fmt::format("no host named '{}'", files_host));
  if (disk.empty()) {
    if (h->disks.empty()) r.fail("files_host", fmt::format("host '{}' has no disk to store the pipelines' files", files_host));
    disk = h->disks.front().name;
  }
  s.files.reserve(s.files.size() + static_cast<std::size_t>(count * (tasks + 1)));
  s.apps.reserve(s.apps.size() + static_cast<std::size_t>(count));
  for (std::int64_t i = 1; i <= count; ++i) {
    auto file_name = [&](std::int64_t k) { return count == 1 ? fmt::format("file_{}", k) : fmt::format("p{}_file_{}", i, k); };
    for (std::int64_t k = 1; k <= tasks + 1; ++k) s.files.push_back({file_name(k), size, files_host, disk, k == 1 && cached});
    AppSpec app{std::to_string(i), host_of(i), {}, memory_limits.max, memory_limits.high, {}};
    app.tasks.reserve(static_cast<std::size_t>(tasks));
    for (std::int64_t k = 1; k <= tasks; ++k) {
      TaskSpec& task = app.tasks.emplace_back();
      task.name = std::to_string(k);
      task.reads = {file_name(k)};
      task.compute = cpu;
      task.writes = {file_name(k + 1)};
      task.chunk_size = chunk;
    }
    s.apps.push_back(std::move(app));
  }
  origins.pipeline_apps = static_cast<std::size_t>(count);
}

// Each name in `after` is one application listed before this one: waiting only on earlier
// ones, the order can have no cycle.
void check_after(TomlReader& a, const AppSpec& app, const std::vector<AppSpec>& before) {
  for (const std::string& name : app.after) {
    const auto named = std::count_if(before.begin(), before.end(), [&](const AppSpec& b) { return b.name == name; });
    if (named == 0) {
      a.fail("after", fmt::format("application '{}' comes after '{}', which is not an application listed before it", app.name, name));
    }
    if (named > 1) a.fail("after", fmt::format("application '{}' comes after '{}', which names {} applications listed before it", app.name, name, named));
  }
}

}  // namespace

void read_pipelines(TomlReader& r, const std::string& file, const ScenarioLimits& limits, Scenario& s, Origins& origins) {
  if (const toml::table* p = r.optional_table("pipelines")) expand_pipelines(*p, s, file, limits, origins);
}

void read_apps(TomlReader& r, const std::string& file, Scenario& s, Origins& origins) {
  const auto apps = r.tables("apps");
  AccessTargets targets(s);
  for (std::size_t i = 0; i < apps.size(); ++i) {
    TomlReader a(*apps[i], r.child_path("apps", i), file);
    origins.apps.push_back({apps[i], a.path(), &file});
    std::vector<Origin>& task_origins = origins.app_tasks.emplace_back();
    AppSpec app;
    app.name = a.name("name", fmt::format("app{}", i + 1));
    app.host = a.name("host", s.hosts.front().name);
    const std::int64_t chunk = a.optional_size("chunk_size").value_or(100'000'000);
    if (chunk <= 0) a.fail("chunk_size", "must be > 0");
    const MemoryLimits memory_limits = read_memory_limits(a, "the application's");
    app.memory_max = memory_limits.max;
    app.memory_high = memory_limits.high;
    app.after = a.names("after");
    check_after(a, app, s.apps);
    const auto tasks = a.tables("tasks");
    if (tasks.empty()) a.fail_table("an application needs at least one [[" + a.path() + ".tasks]]");
    for (std::size_t t = 0; t < tasks.size(); ++t) {
      task_origins.push_back({tasks[t], a.child_path("tasks", t), &file});
      app.tasks.push_back(read_task(*tasks[t], a.child_path("tasks", t), t, chunk, file, targets, false));
    }
    a.finish();
    s.apps.push_back(std::move(app));
  }
}

}  // namespace pagecache::scenario
