#include "workload/prepared_run.hpp"

#include "workload/access_pattern.hpp"

#include <pagecache/error.hpp>
#include <pagecache/units.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <map>

namespace pagecache::workload {

namespace {

// Memory groups are never removed: a run may make at most so many (on one host).
void check_memory_groups(const Scenario& scenario) {
  std::size_t groups = 0;
  for (const AppSpec& app : scenario.apps) groups += app.memory_max > 0 ? 1 : 0;
  for (const WorkflowSpec& w : scenario.workflows) {
    groups += static_cast<std::size_t>(std::count_if(w.tasks.begin(), w.tasks.end(), [](const TaskSpec& t) { return t.memory_limits.max > 0; }));
  }
  if (groups > GroupRef::kMax) {
    throw ConfigError(fmt::format("{} applications and workflow tasks with a memory_max: a run may have at most {} memory groups", groups,
                                  GroupRef::kMax));
  }
}

}  // namespace

PreparedRun::PreparedRun(const Scenario& scenario, const Platform& platform, const FileIndex& files) {
  TaskIndex names;  // the task names met so far: a run of pipelines has a few
  sets_ = platform.file_sets();
  set_names_.reserve(scenario.file_sets.size());  // set_index_ views its strings
  for (const FileSetSpec& set : scenario.file_sets) {
    set_names_.push_back(set.name);
    set_index_.emplace(set_names_.back(), static_cast<std::uint32_t>(set_names_.size() - 1));
  }
  reserve(scenario);
  prepare_applications(scenario.apps, platform, files, names);
  first_workflow_task_ = tasks_.size();
  check_memory_groups(scenario);
  prepare_workflows(scenario.workflows, platform, files, names);
  task_names_.shrink_to_fit();
}

// Exact sizes: at 10^5 pipelines a doubling array's spare half would be tens of MB.
void PreparedRun::reserve(const Scenario& scenario) {
  std::size_t tasks = 0;
  std::size_t files = 0;
  const auto count = [&](const std::vector<TaskSpec>& of) {
    tasks += of.size();
    for (const TaskSpec& t : of) files += t.reads.size() + t.writes.size() + t.deletes.size();
  };
  for (const AppSpec& app : scenario.apps) count(app.tasks);
  for (const WorkflowSpec& w : scenario.workflows) count(w.tasks);
  tasks_.reserve(tasks);
  task_files_.reserve(files);
  apps_.reserve(scenario.apps.size());
}

void PreparedRun::prepare_applications(const std::vector<AppSpec>& apps, const Platform& platform, const FileIndex& files, TaskIndex& names) {
  std::unordered_map<std::string_view, std::uint32_t> earlier;  // only if some application waits (the loader checked the names)
  const bool waits = std::any_of(apps.begin(), apps.end(), [](const AppSpec& app) { return !app.after.empty(); });
  for (const AppSpec& app : apps) {
    if (!app.after.empty()) {
      AppWait& wait = app_waits_.emplace_back(AppWait{static_cast<std::uint32_t>(apps_.size()), {}});
      for (const std::string& name : app.after) wait.after.push_back(earlier.at(name));
    }
    if (waits) earlier.emplace(app.name, static_cast<std::uint32_t>(apps_.size()));
    Host& host = platform.host_named(app.host, "application", app.name);
    // An application with a memory limit is a memory group of its host (a job's cgroup).
    const GroupRef group = app.memory_max > 0 ? host.add_memory_group(app.memory_max, app.memory_high) : GroupRef{};
    apps_.push_back({app.name, &host, static_cast<std::uint32_t>(tasks_.size()), static_cast<std::uint32_t>(app.tasks.size())});
    for (const TaskSpec& task : app.tasks) {
      prepare_task(task, platform.files(), files, names);
      tasks_.back().group = group;
    }
  }
}

void PreparedRun::prepare_workflows(const std::vector<WorkflowSpec>& workflows, const Platform& platform, const FileIndex& files, TaskIndex& names) {
  for (const WorkflowSpec& w : workflows) {
    if (w.hosts.empty()) throw ConfigError(fmt::format("workflow '{}': no host to run on", w.name));
    for (const std::string& h : w.hosts) platform.host_named(h, "workflow", w.name);
    for (const TaskSpec& task : w.tasks) {
      if (!task.host.empty()) platform.host_named(task.host, "task", task.name);
      prepare_task(task, platform.files(), files, names);
    }
  }
}

void PreparedRun::prepare_task(const TaskSpec& task, const std::vector<PlacedFile>& placed, const FileIndex& files, TaskIndex& names) {
  PreparedTask& plan = tasks_.emplace_back();
  const auto [known, added] = names.try_emplace(task.name, static_cast<std::uint32_t>(task_names_.size()));
  if (added) task_names_.push_back(task.name);
  plan.name = known->second;
  const auto add = [&](const std::vector<std::string>& list) {
    for (const std::string& name : list) {
      const auto it = files.find(name);
      if (it == files.end()) throw ConfigError(fmt::format("task '{}': no file named '{}'", task.name, name));
      task_files_.push_back(it->second);
    }
    return static_cast<std::uint32_t>(task_files_.size());
  };
  plan.reads = static_cast<std::uint32_t>(task_files_.size());
  plan.writes = add(task.reads);
  plan.deletes = add(task.writes);
  plan.end = add(task.deletes);
  plan.chunk_size = task.chunk_size;
  std::int64_t reading = 0;
  for (std::uint32_t f = plan.reads; f < plan.writes; ++f) {
    const PlacedFile& file = placed[task_files_[f]];
    reading = std::min(reading + file.host->file_size(file.ref), units::kMaxBytes * 2);
  }
  plan.memory = std::max<std::int64_t>(0, task.memory - reading);
  plan.compute = task.compute;
  plan.fsync = task.fsync;
  plan.direct_io = task.direct_io;
  prepare_accesses(task, plan, placed, files);
}

// Scenarios built in code skip the loader's checks: what the run relies on is checked here.
void PreparedRun::prepare_accesses(const TaskSpec& task, PreparedTask& plan, const std::vector<PlacedFile>& placed, const FileIndex& files) {
  plan.accesses = static_cast<std::uint32_t>(accesses_.size());
  for (const AccessSpec& a : task.accesses) {
    if (a.repeat < 1) throw ConfigError(fmt::format("task '{}': an access needs repeat >= 1", task.name));
    if (!a.file.empty()) {
      if (task.direct_io && a.mode == AccessMode::Append) {
        throw ConfigError(fmt::format("task '{}': appends through O_DIRECT (direct_io) are not modelled yet", task.name));
      }
      prepare_file_access(task, a, accesses_.emplace_back(), placed, files);
      epochs_ += static_cast<std::size_t>(a.repeat);
      continue;
    }
    const auto set = set_index_.find(a.file_set);
    if (set == set_index_.end()) throw ConfigError(fmt::format("task '{}': no file set named '{}'", task.name, a.file_set));
    if (a.count < 0 || a.repeat < 1) {
      throw ConfigError(fmt::format("task '{}': an access of file set '{}' needs count >= 0 and repeat >= 1", task.name, a.file_set));
    }
    PreparedAccess& access = accesses_.emplace_back();
    access.set = sets_[set->second];
    access.set_index = set->second;
    const bool random = a.pattern == AccessPattern::Random;
    access.order = !random ? SampleOrder::Kind::InOrder : a.replacement ? SampleOrder::Kind::WithReplacement : SampleOrder::Kind::Shuffled;
    access.seed = a.seed;
    access.count = a.count > 0 ? a.count : access.set.count;
    access.repeat = a.repeat;
    if (a.replacement && !random) throw ConfigError(fmt::format("task '{}': draws with replacement need the random pattern", task.name));
    if (access.order != SampleOrder::Kind::WithReplacement && access.count > access.set.count) {
      throw ConfigError(fmt::format("task '{}': {} files per epoch of file set '{}', which has {}", task.name, access.count, a.file_set,
                                    access.set.count));
    }
    epochs_ += static_cast<std::size_t>(a.repeat);
  }
  plan.accesses_end = static_cast<std::uint32_t>(accesses_.size());
}

void PreparedRun::prepare_file_access(const TaskSpec& task, const AccessSpec& a, PreparedAccess& access, const std::vector<PlacedFile>& placed,
                             const FileIndex& files) const {
  const auto it = files.find(a.file);
  if (it == files.end()) throw ConfigError(fmt::format("task '{}': no file named '{}'", task.name, a.file));
  access.of_file = true;
  access.file = it->second;
  access.requests = request_pattern(a);
  const PlacedFile& file = placed[it->second];
  const std::string problem = pattern_problem(access.requests, file.host->file_size(file.ref));
  if (!problem.empty()) throw ConfigError(fmt::format("task '{}', access of file '{}': {}", task.name, a.file, problem));
  if (a.replacement && a.pattern != AccessPattern::Random) {
    throw ConfigError(fmt::format("task '{}': draws with replacement need the random pattern", task.name));
  }
  access.writing = a.mode != AccessMode::Read;
  access.advice = a.advice == AccessAdvice::Random       ? ReadAdvice::Random
                  : a.advice == AccessAdvice::Sequential ? ReadAdvice::Sequential
                                                         : ReadAdvice::Normal;
  access.reshuffle = a.reshuffle;
  access.invalidate = a.invalidate;
  access.drop_after = a.drop_after;
  access.runtime = a.runtime;
  access.repeat = a.repeat;
}

WorkflowHosts place_workflow(const WorkflowSpec& w, const Platform& platform, Simulator& sim) {
  WorkflowHosts p;
  std::vector<int> cores;
  std::map<std::string, std::size_t> index;
  const auto add = [&](const std::string& name) {
    const auto [it, added] = index.try_emplace(name, p.hosts.size());
    if (added) {
      p.hosts.push_back(&platform.host(name));
      cores.push_back(platform.cores(name));
    }
    return it->second;
  };
  for (const std::string& h : w.hosts) p.shared.push_back(add(h));
  int most = 0;  // the most cores of a shared host
  for (const std::size_t h : p.shared) most = std::max(most, cores[h]);
  p.own.reserve(w.tasks.size());
  for (const TaskSpec& t : w.tasks) p.own.push_back(t.host.empty() ? CoreScheduler::kShared : add(t.host));
  for (std::size_t i = 0; i < w.tasks.size(); ++i) {
    const TaskSpec& t = w.tasks[i];
    const bool own = p.own[i] != CoreScheduler::kShared;
    if (t.cores > (own ? cores[p.own[i]] : most)) {
      throw ConfigError(fmt::format("workflow '{}', task '{}': needs {} cores, more than {} has", w.name, t.name, t.cores,
                                    own ? "its host" : "any of its workflow's hosts"));
    }
  }
  p.cores = std::make_unique<CoreScheduler>(sim, std::move(cores), p.shared);
  return p;
}

}  // namespace pagecache::workload
