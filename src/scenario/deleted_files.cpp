#include "scenario/deleted_files.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <optional>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace pagecache::scenario {

namespace {

// An application's tasks run one after the other: a file its task deleted is gone for the
// tasks after, until one of them writes it again.
void check_application(const AppSpec& app, std::size_t a, const Origins& origins) {
  std::unordered_map<std::string_view, std::size_t> deleted_by;  // file -> the task that deleted it
  for (std::size_t t = 0; t < app.tasks.size(); ++t) {
    const TaskSpec& task = app.tasks[t];
    for (const std::string& file : task.reads) {
      const auto it = deleted_by.find(file);
      if (it == deleted_by.end()) continue;
      origins.app_task(a, t).fail("read", fmt::format("task '{}' of application '{}' reads file '{}', which its task '{}' deleted before "
                                                      "(an application's tasks run one after the other)",
                                                      task.name, app.name, file, app.tasks[it->second].name));
    }
    for (const std::string& file : task.writes) deleted_by.erase(file);
    for (const std::string& file : task.deletes) deleted_by[file] = t;
  }
}

// Which tasks of a workflow run after which: a task waits for those it names in `after` and
// for the writers of what it reads, and so, through them, for theirs.
class WorkflowOrder {
 public:
  explicit WorkflowOrder(const WorkflowSpec& w) : next_(w.tasks.size()), seen_(w.tasks.size(), 0) {
    std::unordered_map<std::string_view, std::size_t> by_name;
    for (std::size_t t = 0; t < w.tasks.size(); ++t) {
      by_name.emplace(w.tasks[t].name, t);
      for (const std::string& file : w.tasks[t].writes) writer_.emplace(file, t);
    }
    for (std::size_t t = 0; t < w.tasks.size(); ++t) {
      for (const std::string& before : w.tasks[t].after) {
        if (const auto it = by_name.find(before); it != by_name.end()) next_[it->second].push_back(t);
      }
      for (const std::string& file : w.tasks[t].reads) {
        if (const auto it = writer_.find(file); it != writer_.end() && it->second != t) next_[it->second].push_back(t);
      }
    }
    for (const auto& n : next_) edges_ += n.size();
  }

  /// The task writing `file`, if one does (the loader allows one).
  std::optional<std::size_t> writer(std::string_view file) const {
    const auto it = writer_.find(file);
    return it == writer_.end() ? std::nullopt : std::optional(it->second);
  }

  /// Whether `later` starts only after `first` ended; nullopt once the searches have looked at
  /// so many dependencies that the rest is left to the run (a workflow of 10^6 tasks deleting
  /// many files must still load in seconds).
  std::optional<bool> follows(std::size_t first, std::size_t later) {
    if (first != from_) {
      if (budget_ < edges_) return std::nullopt;
      ++stamp_;
      from_ = first;
      std::vector<std::size_t> stack{first};
      while (!stack.empty()) {
        const std::size_t t = stack.back();
        stack.pop_back();
        budget_ -= next_[t].size();
        for (const std::size_t n : next_[t]) {
          if (seen_[n] != stamp_) {
            seen_[n] = stamp_;
            stack.push_back(n);
          }
        }
      }
    }
    return seen_[later] == stamp_;
  }

 private:
  std::vector<std::vector<std::size_t>> next_;  // per task: the tasks that wait for it
  std::unordered_map<std::string_view, std::size_t> writer_;
  std::vector<std::uint32_t> seen_;  // stamp_ where the last search reached
  std::uint32_t stamp_ = 0;
  std::size_t from_ = static_cast<std::size_t>(-1);
  std::size_t edges_ = 0;
  std::size_t budget_ = 20'000'000;  // dependencies the searches may still look at
};

// A workflow task reading a file that a task it runs after deleted, unless the file is written
// again in between: by a task running after the deleter (no error), or by one in no fixed order
// with it (the run decides).
void check_workflow(const WorkflowSpec& w, std::size_t index, const Origins& origins) {
  std::unordered_map<std::string_view, std::vector<std::size_t>> readers;
  bool deletes = false;
  for (std::size_t t = 0; t < w.tasks.size(); ++t) {
    deletes = deletes || !w.tasks[t].deletes.empty();
    for (const std::string& file : w.tasks[t].reads) readers[file].push_back(t);
  }
  if (!deletes) return;
  WorkflowOrder order(w);
  for (std::size_t d = 0; d < w.tasks.size(); ++d) {
    for (const std::string& file : w.tasks[d].deletes) {
      const auto it = readers.find(file);
      if (it == readers.end()) continue;
      // A reader starting after the deletion (not the deleter itself, which reads first).
      const auto reader = std::find_if(it->second.begin(), it->second.end(),
                                       [&](std::size_t r) { return r != d && order.follows(d, r).value_or(false); });
      if (reader == it->second.end()) continue;
      // Unless the file's writer wrote it before the deletion, it may have been written again
      // in between: the run decides.
      const std::optional<std::size_t> writer = order.writer(file);
      if (writer && *writer != d && !order.follows(*writer, d).value_or(false)) continue;
      const TaskSpec& r = w.tasks[*reader];
      origins.workflow_tasks[index][*reader].fail(
          "read", fmt::format("task '{}' of workflow '{}' reads file '{}', which task '{}' deletes before it: '{}' starts only after "
                              "'{}' has ended (it waits for it through `after` or the files it reads){}",
                              r.name, w.name, file, w.tasks[d].name, r.name, w.tasks[d].name,
                              writer && *writer != d ? fmt::format("; its writer, '{}', runs before '{}'", w.tasks[*writer].name, w.tasks[d].name) : ""));
    }
  }
}

}  // namespace

void check_reads_of_deleted_files(const Scenario& s, const Origins& origins) {
  for (std::size_t a = 0; a < s.apps.size(); ++a) {
    const auto& tasks = s.apps[a].tasks;
    if (std::any_of(tasks.begin(), tasks.end(), [](const TaskSpec& t) { return !t.deletes.empty(); })) check_application(s.apps[a], a, origins);
  }
  for (std::size_t w = 0; w < s.workflows.size(); ++w) check_workflow(s.workflows[w], w, origins);
}

}  // namespace pagecache::scenario
