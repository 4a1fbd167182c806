#pragma once
// A workflow instance read from JSON into a neutral form: tasks (runtime, cores, memory, the
// machines that ran them), the files they read and write (bytes), and their dependencies, as
// indices. Two formats: WfFormat 1.5 and 1.6 (WfCommons: `workflow.specification` for the
// graph and the files, `workflow.execution` for what was measured; 1.6 adds optional figures
// about both, `metrics`) and the format before it that WRENCH 2.x reads (`workflow.tasks[]`,
// each with its own `files[]` marked input or output; also WfFormat 1.3 and 1.4). Nothing here knows pcsim's scenarios: turning a workflow into one is
// the caller's business.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace pagecache::formats::wfformat {

struct WfFile {
  std::string id;
  std::int64_t size = 0;  ///< bytes
};

struct WfTask {
  std::string id;                     ///< unique; WfFormat 1.5 `id` (falls back to `name`); old format `name`
  std::string name;                   ///< 1.5 `name` (falls back to `id`); old format `name`
  double runtime = 0;                 ///< seconds: 1.5 execution.tasks[].runtimeInSeconds; old `runtime`/`runtimeInSeconds`
  int cores = 1;                      ///< 1.5 execution coreCount, else 1; old `cores`
  std::int64_t memory = 0;            ///< bytes, 0 if not recorded: 1.5 execution memoryInBytes; old `memory`/`memoryInBytes`
  double avg_cpu = -1;                ///< percent (1.5 execution avgCPU; old `avgCPU`), -1 if absent
  std::vector<std::string> machines;  ///< 1.5 execution machines (node names); old `machine`/`machines` if present
  std::vector<std::size_t> parents;   ///< indices into tasks, each once, in the order listed
  std::vector<std::size_t> inputs;    ///< indices into files, each once, in the order listed
  std::vector<std::size_t> outputs;   ///< indices into files, each once, in the order listed
};

/// A recorded machine's CPU speed as the instance gives it, read only by compute = "speed"
/// (workflow_speed.hpp), so that reading it can refuse nothing: 1.5 read exactly as before.
struct WfMachineSpeed {
  /// MHz: 1.5 and 1.6 execution.machines[].cpu.speedInMHz, old format workflow.machines[].cpu.speed
  /// (MHz too, WfFormat 1.3 and 1.4). -1 if absent; NaN if not a number; else as written (0 too).
  double mhz = -1;
  std::string place;  ///< for messages: "FILE: workflow.execution.machines[0] (machine 'x'): cpu.speedInMHz"
};

struct WfWorkflow {
  std::string file;
  std::string name;
  std::string format;                 ///< "WfFormat 1.5", "WfFormat 1.6" or "WRENCH 2.x (schema before 1.5)"
  double makespan = -1;               ///< seconds: execution.makespanInSeconds (old: makespan/makespanInSeconds), -1 if absent
  std::vector<WfFile> files;          ///< specification.files order (old format: first-seen order)
  std::vector<WfTask> tasks;          ///< specification order; NOT necessarily topological (but acyclic)
  std::vector<std::string> machines;  ///< execution.machines[].nodeName (old: workflow.machines[]), in order
  std::vector<WfMachineSpeed> machine_speeds;  ///< per machines[i]
  /// What was accepted but looks wrong, one line each in the form of the errors ("FILE: PATH
  /// (task 'x'): KEY: ..."): children that disagree with the parents (nighres_workflow.json's
  /// extract_brain_region lists itself), an old-format file given two sizes (the first is kept,
  /// as WRENCH does), a WfFormat file without an execution section (every runtime 0). At most
  /// kMaxWorkflowWarnings, the last saying how many more there were.
  std::vector<std::string> warnings;
};

/// The most warnings a WfWorkflow keeps: a hostile file could raise one per file mention.
inline constexpr std::size_t kMaxWorkflowWarnings = 100;

/// Parses a workflow instance. Throws pagecache::ConfigError (<pagecache/error.hpp>) naming the file, the line and
/// column for malformed JSON ("FILE:LINE:COL: malformed JSON: ..."), and for every other problem the JSON path of the
/// element at fault and the key ("FILE: workflow.specification.tasks[3] (task 'x'): parents: unknown task 'y'").
/// `max_tasks`/`max_files` bound what is accepted (a hostile file must fail fast, naming the count).
///
/// The format: `schemaVersion` "1.5" is WfFormat 1.5, "1.6" WfFormat 1.6 (1.5 and its optional
/// `metrics`: each figure a number of the right kind, else refused; one that disagrees with the
/// workflow is a warning naming both); no `schemaVersion`, or "1.0" to "1.4", with a
/// `workflow.tasks` array is the old format; anything else is refused, naming `schemaVersion`.
/// Refused: wrong JSON types; missing ids, sizes or (old format) runtimes; sizes that are negative,
/// fractional or above 2^60; runtimes negative or above 10^9 s; cores outside 1 to 10^6; a reference
/// to an unknown task or file, or to a machine the workflow's machine list (if any) lacks; repeated
/// ids; an execution record without its task, or, when there is an execution section, a task
/// without its record; a dependency cycle (its tasks named); nesting deeper than 128 levels. Parents
/// alone make the dependencies: `children` (old `childrens`) must name known tasks but may disagree
/// (a warning). Ids repeated within one list count once. Unknown keys are ignored.
WfWorkflow read_workflow_json(const std::string& text, const std::string& file, std::int64_t max_tasks, std::int64_t max_files);

}  // namespace pagecache::formats::wfformat
