#pragma once
// PreparedRun: the scenario's applications and workflow tasks as their run reads them, made once
// before it, all tasks prepared side by side, so that an I/O phase looks no name up and
// reads no cold string; and the placement of a workflow's tasks on its hosts' cores.

#include "workload/core_scheduler.hpp"
#include "workload/platform.hpp"
#include "workload/request_pattern.hpp"
#include "workload/sample_order.hpp"

#include <pagecache/host.hpp>
#include <pagecache/scenario.hpp>
#include <pagecache/simulator.hpp>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace pagecache::workload {

/// A task as its run reads it. Its files are ranges of one array of indices into the
/// platform's files (PreparedRun::file), in the order of the task's lists.
struct PreparedTask {
  std::uint32_t reads = 0;  // first read; the writes follow the reads, the deletes the writes
  std::uint32_t writes = 0;
  std::uint32_t deletes = 0;
  std::uint32_t end = 0;
  std::uint32_t accesses = 0;  // its accesses: PreparedRun::access(i) for i in [accesses, accesses_end)
  std::uint32_t accesses_end = 0;
  std::int64_t chunk_size = 0;
  std::int64_t memory = 0;  // held besides the buffers of what it reads
  double compute = 0.0;
  std::uint32_t name = 0;  // PreparedRun::task_name
  bool fsync = false;
  bool direct_io = false;
  GroupRef group;  // its application's memory group, if it has one
};

/// An access (AccessSpec) as its run reads it: its set's files, the order it visits them in; or
/// its file and the requests it makes of it.
struct PreparedAccess {
  bool of_file = false;
  std::uint32_t file = 0;    // of_file: in Platform::files()
  RequestPattern requests;   // of_file
  bool writing = false;      // of_file: writes (in place or appends), else reads
  ReadAdvice advice = ReadAdvice::Normal;
  bool reshuffle = true;     // of_file: random epochs each drawn anew (AccessSpec::reshuffle)
  bool invalidate = false;   // of_file: the region's clean data dropped before each epoch
  bool drop_after = false;   // of_file: and after each epoch
  double runtime = 0.0;      // of_file: no request after this long (0: no limit)
  PlacedFileSet set;
  std::uint32_t set_index = 0;  // in the scenario's file sets (PreparedRun::set_name)
  SampleOrder::Kind order = SampleOrder::Kind::InOrder;
  std::uint64_t seed = 0;
  std::int64_t count = 0;  // files per epoch
  std::int64_t repeat = 1;
};

/// An application as its run reads it: its prepared tasks are `tasks` from `first`.
struct PreparedApp {
  std::string name;
  Host* host;
  std::uint32_t first;
  std::uint32_t tasks;
};

/// An application that starts after others have ended (AppSpec::after), by index in apps().
struct AppWait {
  std::uint32_t app;
  std::vector<std::uint32_t> after;
};

class PreparedRun {
 public:
  /// PreparedRun every task of `scenario` on `platform` (which gives the applications' memory groups);
  /// `files` indexes the platform's files by name.
  PreparedRun(const Scenario& scenario, const Platform& platform, const FileIndex& files);

  /// Per application, in order; the workflows' prepared tasks, in their order, from workflow_tasks().
  const std::vector<PreparedApp>& apps() const noexcept { return apps_; }
  /// The applications that wait for others, in order (few or none: kept apart from PreparedApp).
  const std::vector<AppWait>& app_waits() const noexcept { return app_waits_; }
  const PreparedTask* workflow_tasks() const noexcept { return tasks_.data() + first_workflow_task_; }
  std::span<const PreparedTask> tasks_of(const PreparedApp& app) const noexcept { return {tasks_.data() + app.first, app.tasks}; }

  const std::string& task_name(const PreparedTask& plan) const noexcept { return task_names_[plan.name]; }
  /// The file of a task's list, `f` in [reads, end) of the prepared task: its index in Platform::files().
  std::uint32_t file(std::uint32_t f) const noexcept { return task_files_[f]; }
  const PreparedAccess& access(std::uint32_t i) const noexcept { return accesses_[i]; }
  const std::string& set_name(const PreparedAccess& access) const noexcept { return set_names_[access.set_index]; }
  /// The run's timeline rows: three per task, one per access and epoch; and of them the I/O
  /// phases (after which the cache contents are recorded).
  std::size_t timeline_rows() const noexcept { return 3 * tasks_.size() + epochs_; }
  std::size_t io_phases() const noexcept { return 2 * tasks_.size() + epochs_; }

 private:
  using TaskIndex = std::unordered_map<std::string_view, std::uint32_t>;  // in task_names_

  void reserve(const Scenario& scenario);
  void prepare_applications(const std::vector<AppSpec>& apps, const Platform& platform, const FileIndex& files, TaskIndex& names);
  void prepare_workflows(const std::vector<WorkflowSpec>& workflows, const Platform& platform, const FileIndex& files, TaskIndex& names);
  void prepare_task(const TaskSpec& task, const std::vector<PlacedFile>& placed, const FileIndex& files, TaskIndex& names);
  void prepare_accesses(const TaskSpec& task, PreparedTask& plan, const std::vector<PlacedFile>& placed, const FileIndex& files);
  void prepare_file_access(const TaskSpec& task, const AccessSpec& a, PreparedAccess& access, const std::vector<PlacedFile>& placed,
                        const FileIndex& files) const;

  std::vector<PreparedApp> apps_;
  std::vector<AppWait> app_waits_;
  std::vector<PreparedTask> tasks_;  // per task, apps' then workflows', in order
  std::size_t first_workflow_task_ = 0;
  std::vector<std::string> task_names_;       // what PreparedTask::name names, each name once
  std::vector<std::uint32_t> task_files_;  // the files of the tasks' lists, in Platform::files()
  std::vector<PreparedAccess> accesses_;          // the tasks' accesses, task after task
  std::vector<std::string> set_names_;        // per file set
  std::unordered_map<std::string_view, std::uint32_t> set_index_;  // in set_names_
  std::vector<PlacedFileSet> sets_;           // per file set
  std::size_t epochs_ = 0;                    // of all accesses
};

/// The hosts a workflow's tasks may run on, and the scheduler of their cores: the workflow's
/// hosts, then those its tasks name.
struct WorkflowHosts {
  std::vector<Host*> hosts;
  std::unique_ptr<CoreScheduler> cores;
  std::vector<std::size_t> shared;  // the workflow's hosts
  std::vector<std::size_t> own;     // per task: its own host, if it names one (else CoreScheduler::kShared)
};

/// Where `w`'s tasks may run; ConfigError if a task needs more cores than its hosts have.
WorkflowHosts place_workflow(const WorkflowSpec& w, const Platform& platform, Simulator& sim);

}  // namespace pagecache::workload
