#pragma once
// Runner: the run of a scenario (run_scenario, pagecache/run.hpp). It builds the scenario's
// Platform and PreparedRun, runs each application and each workflow task as a process to the end,
// and reports what happens through a RunTrace and the hosts' memory through a MemoryProfile.

#include "workload/deleted_files.hpp"
#include "workload/memory_profile.hpp"
#include "workload/prepared_run.hpp"
#include "workload/platform.hpp"
#include "workload/run_trace.hpp"

#include <pagecache/event.hpp>
#include <pagecache/fair_share.hpp>
#include <pagecache/host.hpp>
#include <pagecache/run.hpp>
#include <pagecache/scenario.hpp>
#include <pagecache/simulator.hpp>
#include <pagecache/task.hpp>

#include <chrono>
#include <cstddef>
#include <deque>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace pagecache::workload {

class Runner {
 public:
  /// `owned`: the scenario is the runner's; its applications and files, all the run needs of
  /// them planned, are freed before the run starts.
  Runner(const Scenario& scenario, const RunOptions& options, Scenario* owned = nullptr);
  Runner(const Runner&) = delete;
  Runner& operator=(const Runner&) = delete;

  /// Runs the scenario to the end, once.
  RunResult run();

 private:
  // `files` indexes the files for planning alone: it is freed once the runner is made.
  Runner(const Scenario& scenario, const RunOptions& options, Scenario* owned, FileIndex&& files);

  void start_applications();
  void start_workflows();
  void simulate();
  void summarize(std::chrono::steady_clock::time_point wall_start);

  Task<void> run_tasks(const std::string& app, std::span<const PreparedTask> plans, Host& host, bool ends_app);
  /// Application `index` once `before` have ended; then its end is app_done_[index].
  Task<void> run_app_in_order(std::size_t index, std::vector<Event*> before);
  Task<void> run_accesses(const std::string& app, const PreparedTask& plan, Host& host, Thread thread, bool ends_app);
  Task<void> read_file_set(const std::string& app, const PreparedTask& plan, const PreparedAccess& access, Host& host, Thread thread);
  Task<void> access_file(const std::string& app, const PreparedTask& plan, const PreparedAccess& access, Host& host, Thread thread, bool ends_app);
  Task<void> run_workflow_task(const WorkflowSpec& w, const TaskSpec& task, const PreparedTask& plan, WorkflowHosts& hosts, std::size_t index,
                               std::vector<Event*> prerequisites, Event& done);
  void finish_one();

  // The file of a task's list: `f` in [reads, end) of its plan.
  const PlacedFile& task_file(std::uint32_t f) const { return platform_.files()[prepared_.file(f)]; }

  const Scenario& scenario_;
  const RunOptions& options_;
  Simulator sim_;
  FairShare share_;
  Platform platform_;
  PreparedRun prepared_;
  MemoryProfile memory_;
  DeletedFiles deleted_;
  std::optional<RunTrace> trace_;                // from the run's start
  std::deque<WorkflowHosts> workflow_hosts_;     // per workflow
  std::deque<Event> app_done_;  // per application, when some application waits (else empty)
  std::deque<std::deque<Event>> workflow_done_;  // per workflow, its tasks' ends in workflow order
  int running_ = 0;                              // processes not yet ended: applications, workflow tasks
};

}  // namespace pagecache::workload
