#pragma once
// A workflow instance (read by read_workflow_json) as a scenario's workflow and files.
//
// Each task reads its input files, computes for its recorded runtime, writes its output files,
// and holds its recorded memory while it runs; it starts once its parents have ended and its
// host has the cores it needs. A task whose recorded machine is a host of the platform runs
// there; the others go to the first of the workflow's hosts with enough free cores. Every file
// is stored on one host (a shared file system, as the instances were recorded on), which the
// tasks on other hosts reach over the platform's routes.

#include <pagecache/scenario.hpp>

#include "scenario/origins.hpp"
#include "formats/wfformat/workflow_json.hpp"

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace pagecache::scenario {

/// How a recorded runtime becomes the compute phase.
enum class ComputeFrom {
  /// The whole recorded runtime (WRENCH's and WfCommons' simulators' convention): the I/O the
  /// real run did inside it is simulated again on top, so I/O-heavy tasks come out long.
  Runtime,
  /// The runtime times the CPU share the instance records (avgCPU / 100 / cores, at most 1):
  /// the time the task's cores were busy; the rest, I/O among it, is left to the simulation.
  CpuShare,
  /// The whole runtime times the recorded machine's speed over the speed of the host the task
  /// runs on (WRENCH's scaling; workflow_speed.hpp says how and what is refused).
  Speed,
};

struct WorkflowImport {
  std::string name;                ///< empty: the instance's
  /// Empty: the first recorded machine the platform has, else the first of `hosts`, else the
  /// platform's first host.
  std::string files_host;
  std::string files_disk;  ///< empty: the files host's first disk
  /// Empty: the recorded machines the platform has; else, if files_host is given, every host
  /// but that one (a storage server); else the files host alone.
  std::vector<std::string> hosts;
  bool inputs_cached = false;      ///< the files no task writes start in the files host's page cache
  ComputeFrom compute = ComputeFrom::Runtime;
  /// compute = "speed": the flop/s of a recorded machine the instance gives no speed for.
  std::optional<double> reference_speed;
  std::int64_t chunk_size = 100'000'000;
  MemoryLimits memory_limits;  ///< of each task's memory group (none by default)
};

/// Adds `workflow` and its files to `s` (whose hosts are read), their origins to `origins`.
/// `fail(key, message)` reports an option that does not fit the platform and must throw.
void add_json_workflow(const formats::wfformat::WfWorkflow& workflow, const WorkflowImport& options, Scenario& s, Origins& origins,
                       const std::function<void(const std::string&, const std::string&)>& fail);

}  // namespace pagecache::scenario
