// WfFormat 1.5 (wfcommons-schema.json): workflow.specification holds the graph (tasks with
// parents, children, inputFiles, outputFiles; files with sizeInBytes), workflow.execution what
// one run measured (a record per task: runtimeInSeconds, coreCount, memoryInBytes, avgCPU,
// machines; the machines by nodeName; the makespan).

#include "formats/wfformat/readers.hpp"

#include <pagecache/units.hpp>

#include <fmt/format.h>

#include <limits>

namespace pagecache::formats::wfformat {

namespace {

using nlohmann::json;

constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();

NameIndex read_files(const JsonObject& spec, const WorkflowLimits& limits, WfWorkflow& out) {
  static const json::array_t kNoFiles;
  const json::array_t* files = spec.optional_array("files");
  if (files == nullptr) files = &kNoFiles;
  check_count(spec, "files", files->size(), limits.max_files, "files");
  NameIndex ids;
  out.files.reserve(files->size());
  for (std::size_t i = 0; i < files->size(); ++i) {
    JsonObject file = spec.item("files", *files, i);
    std::string id = file.required_string("id", "every file needs an id");
    file.describe("file " + quote_name(id));
    const auto [first, added] = ids.insert(id);
    if (!added) file.fail("id", fmt::format("a second file {}: the first is files[{}]", quote_name(id), first));
    const std::int64_t size = file.required_bytes("sizeInBytes", "every file needs its size in bytes");
    out.files.push_back({std::move(id), size});
  }
  return ids;
}

// Execution records are matched to tasks by id. With an execution section, every task needs
// its record: a missing one is a truncated or hand-merged file, and a runtime of 0 taken for it
// would skew every result quietly. A file without one is a specification only (WfFormat
// requires no execution), read with every runtime 0 and a warning.
void read_execution(const JsonObject& workflow, const NameIndex& task_ids, const std::vector<JsonObject>& tasks,
                    const WorkflowLimits& limits, WfWorkflow& out, Warnings& warnings) {
  const std::optional<JsonObject> execution = workflow.optional_object("execution");
  if (!execution) {
    warnings.add(workflow.message("execution", "missing, so nothing was measured: every task's runtime is 0 s"));
    return;
  }
  out.makespan = execution->optional_number("makespanInSeconds", 0, units::kMaxSeconds).value_or(-1);
  const NameIndex machines = read_machine_list(*execution, "machines", "speedInMHz", out);
  const std::string machines_path = execution->path_of("machines");
  const json::array_t& records = execution->required_array("tasks", "a record per task, with its runtimeInSeconds");
  check_count(*execution, "tasks", records.size(), limits.max_tasks, "tasks");
  std::vector<std::size_t> record_of(out.tasks.size(), kNone);
  for (std::size_t j = 0; j < records.size(); ++j) {
    JsonObject record = execution->item("tasks", records, j);
    const std::string id = record.required_string("id", "the id of the task in workflow.specification.tasks");
    record.describe("task " + quote_name(id));
    const std::optional<std::size_t> index = task_ids.find(id);
    if (!index) record.fail("id", fmt::format("no task {} in workflow.specification.tasks", quote_name(id)));
    if (record_of[*index] != kNone) record.fail("id", fmt::format("a second record for task {}: the first is tasks[{}]", quote_name(id), record_of[*index]));
    record_of[*index] = j;
    WfTask& task = out.tasks[*index];
    task.runtime = record.required_number("runtimeInSeconds", 0, units::kMaxSeconds, "the task's measured runtime in seconds");
    task.cores = static_cast<int>(record.optional_whole("coreCount", 1, kMaxCores).value_or(1));
    task.memory = record.optional_rounded_bytes("memoryInBytes").value_or(0);
    task.avg_cpu = record.optional_number("avgCPU", 0, kMaxAvgCpu).value_or(-1);
    task.machines = read_task_machines(record, {"machines"}, machines, machines_path);
  }
  for (std::size_t i = 0; i < tasks.size(); ++i) {
    if (record_of[i] == kNone) {
      tasks[i].fail("id", fmt::format("no record in {}, so no runtime (a file without an execution section reads as a specification, "
                                      "every runtime 0 s)",
                                      execution->path_of("tasks")));
    }
  }
}

}  // namespace

std::string read_wfformat_15(const JsonObject& root, const WorkflowLimits& limits, WfWorkflow& out, Warnings& warnings) {
  const JsonObject workflow = root.required_object("workflow", "the workflow's specification and execution");
  const JsonObject spec = workflow.required_object("specification", "WfFormat 1.5 keeps the tasks and files in workflow.specification");
  const json::array_t& task_array = spec.required_array("tasks", "the workflow's tasks");
  check_count(spec, "tasks", task_array.size(), limits.max_tasks, "tasks");
  if (task_array.empty()) spec.fail("tasks", "empty: a workflow needs at least one task");
  const NameIndex file_ids = read_files(spec, limits, out);

  // First the ids, so that a task may name a parent listed after it.
  NameIndex task_ids;
  std::vector<JsonObject> tasks;
  tasks.reserve(task_array.size());
  out.tasks.reserve(task_array.size());
  for (std::size_t i = 0; i < task_array.size(); ++i) {
    JsonObject t = spec.item("tasks", task_array, i);
    if (t.find("id") == nullptr && t.find("name") == nullptr) t.fail("id", "missing: every task needs an id");
    const std::string_view id_key = t.find("id") != nullptr ? "id" : "name";
    WfTask task;
    task.id = t.required_string(id_key, "");
    task.name = t.find("name") != nullptr ? t.required_string("name", "") : task.id;
    t.describe("task " + quote_name(task.id));
    const auto [first, added] = task_ids.insert(task.id);
    if (!added) t.fail(id_key, fmt::format("a second task {}: the first is tasks[{}]", quote_name(task.id), first));
    out.tasks.push_back(std::move(task));
    tasks.push_back(std::move(t));
  }

  ReferenceReader task_refs(task_ids, "task");
  ReferenceReader file_refs(file_ids, "file");
  std::vector<ListedChildren> listed;
  listed.reserve(tasks.size());
  for (std::size_t i = 0; i < tasks.size(); ++i) {
    const JsonObject& t = tasks[i];
    WfTask& task = out.tasks[i];
    task.parents = read_parents(t, i, task_refs);
    const bool has_children = t.find("children") != nullptr;
    listed.push_back({t, has_children ? "children" : "", has_children ? task_refs.read(t, "children") : std::vector<std::size_t>{}});
    task.inputs = file_refs.read(t, "inputFiles");
    task.outputs = file_refs.read(t, "outputFiles");
  }
  warn_about_children(out.tasks, listed, warnings);
  read_execution(workflow, task_ids, tasks, limits, out, warnings);
  return spec.path_of("tasks");
}

}  // namespace pagecache::formats::wfformat
