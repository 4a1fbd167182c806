// The format before WfFormat 1.5, as WRENCH 2.x and the WRENCH page-cache experiments read it
// (nighres_workflow.json, simple_workflow.json): workflow.tasks[], each with its name (its id:
// parents name tasks by name), runtime, cores, memory, parents, childrens, and files[] marked
// "link": "input" or "output" with their name and size. WfFormat 1.3 and 1.4 wrote the same
// shape with runtimeInSeconds, sizeInBytes, memoryInBytes, children, machine and a file path;
// those spellings are read too (either, never both). Memory is bytes, as in the WRENCH inputs
// (4000000000 for 4 GB); WfFormat 1.3 meant kB, which its migration to 1.4 multiplies by 1000.

#include "formats/wfformat/readers.hpp"

#include <pagecache/units.hpp>

#include <fmt/format.h>

namespace pagecache::formats::wfformat {

namespace {

using nlohmann::json;

bool same_letters(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if ((a[i] | 0x20) != b[i]) return false;  // b is lower-case letters
  }
  return true;
}

// Files appear inside the tasks that use them; the first mention makes the file.
class FileCollector {
 public:
  FileCollector(const WorkflowLimits& limits, WfWorkflow& out, Warnings& warnings) : limits_(&limits), out_(&out), warnings_(&warnings) {}

  // Adds the files of `task` (index `t`) to its inputs and outputs, each once per list.
  void read(const JsonObject& task, std::size_t t) {
    const json::array_t* files = task.optional_array("files");
    if (files == nullptr) return;
    for (std::size_t k = 0; k < files->size(); ++k) {
      JsonObject file = task.item("files", *files, k);
      std::string id = file.required_string("name", "every file needs its name");
      // WfFormat 1.4's files may carry a folder; its migration to 1.5 makes the id path + name.
      if (const std::optional<std::string> path = file.optional_string("path")) id = *path + id;
      file.describe("file " + quote_name(id));
      const std::string link = file.required_string("link", "\"input\" or \"output\"");
      const bool input = same_letters(link, "input");
      if (!input && !same_letters(link, "output")) file.fail("link", fmt::format("expected \"input\" or \"output\", got {}", quote_name(link)));
      const std::string_view size_key = file.one_of({"sizeInBytes", "size"});
      const std::int64_t size = file.required_bytes(size_key.empty() ? "size" : size_key, "every file needs its size in bytes");
      const std::size_t index = add(file, id, size_key, size);
      // Marks are per task and list: 2t + 1 for inputs, 2t + 2 for outputs.
      const std::size_t list = 2 * t + (input ? 1 : 2);
      if (mark_[index] == list) continue;
      mark_[index] = list;
      (input ? out_->tasks[t].inputs : out_->tasks[t].outputs).push_back(index);
    }
  }

 private:
  // A file given two sizes keeps the first, as WRENCH does (it adds a file the first time it
  // meets its name, then only looks it up): nighres_workflow.json gives two of its files 98 MB
  // where extract_brain_region writes them and 590 MB where cruise_cortex_extraction reads them,
  // and must load. A warning says so.
  std::size_t add(const JsonObject& file, const std::string& id, std::string_view size_key, std::int64_t size) {
    const auto [index, added] = ids_.insert(id);
    if (added) {
      check_count(file, "name", ids_.size(), limits_->max_files, "distinct files");
      out_->files.push_back({id, size});
      first_seen_.push_back(file.path());
      mark_.push_back(0);
    } else if (out_->files[index].size != size) {
      warnings_->add(file.message(size_key, fmt::format("{} bytes here, {} at {}, where the file first appears; the first is kept, as in WRENCH",
                                                        size, out_->files[index].size, first_seen_[index])));
    }
    return index;
  }

  const WorkflowLimits* limits_;
  WfWorkflow* out_;
  Warnings* warnings_;
  NameIndex ids_;
  std::vector<std::string> first_seen_;  // per file, the path of its first mention
  std::vector<std::size_t> mark_;        // per file, the list it was last added to
};

}  // namespace

std::string read_wrench_tasks(const JsonObject& root, const WorkflowLimits& limits, WfWorkflow& out, Warnings& warnings) {
  const JsonObject workflow = root.required_object("workflow", "the workflow's tasks");
  const json::array_t& task_array = workflow.required_array("tasks", "the workflow's tasks");
  check_count(workflow, "tasks", task_array.size(), limits.max_tasks, "tasks");
  if (task_array.empty()) workflow.fail("tasks", "empty: a workflow needs at least one task");
  if (const std::string_view key = workflow.one_of({"makespanInSeconds", "makespan"}); !key.empty()) {
    out.makespan = *workflow.optional_number(key, 0, units::kMaxSeconds);
  }
  const NameIndex machines = read_machine_list(workflow, "machines", "speed", out);
  const std::string machines_path = workflow.path_of("machines");

  // First the names, so that a task may name a parent listed after it.
  NameIndex task_ids;
  std::vector<JsonObject> tasks;
  tasks.reserve(task_array.size());
  out.tasks.reserve(task_array.size());
  for (std::size_t i = 0; i < task_array.size(); ++i) {
    JsonObject t = workflow.item("tasks", task_array, i);
    WfTask task;
    task.id = t.required_string("name", "every task needs a name, by which its children name it");
    task.name = task.id;
    t.describe("task " + quote_name(task.id));
    const auto [first, added] = task_ids.insert(task.id);
    if (!added) t.fail("name", fmt::format("a second task {}: the first is tasks[{}]", quote_name(task.id), first));
    out.tasks.push_back(std::move(task));
    tasks.push_back(std::move(t));
  }

  ReferenceReader task_refs(task_ids, "task");
  FileCollector files(limits, out, warnings);
  std::vector<ListedChildren> listed;
  listed.reserve(tasks.size());
  for (std::size_t i = 0; i < tasks.size(); ++i) {
    const JsonObject& t = tasks[i];
    WfTask& task = out.tasks[i];
    const std::string_view runtime_key = t.one_of({"runtimeInSeconds", "runtime"});
    task.runtime = t.required_number(runtime_key.empty() ? "runtime" : runtime_key, 0, units::kMaxSeconds, "the task's runtime in seconds");
    task.cores = static_cast<int>(t.optional_whole("cores", 1, kMaxCores).value_or(1));
    if (const std::string_view key = t.one_of({"memoryInBytes", "memory"}); !key.empty()) task.memory = *t.optional_rounded_bytes(key);
    task.avg_cpu = t.optional_number("avgCPU", 0, kMaxAvgCpu).value_or(-1);
    task.machines = read_task_machines(t, {"machines", "machine"}, machines, machines_path);
    task.parents = read_parents(t, i, task_refs);
    const std::string_view children_key = t.one_of({"children", "childrens"});
    listed.push_back({t, std::string(children_key), children_key.empty() ? std::vector<std::size_t>{} : task_refs.read(t, children_key)});
    files.read(t, i);
  }
  warn_about_children(out.tasks, listed, warnings);
  return workflow.path_of("tasks");
}

}  // namespace pagecache::formats::wfformat
