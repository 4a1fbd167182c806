// Reading a workflow instance: JSON text -> document -> format told by schemaVersion -> that
// format's reader -> the dependency graph checked for cycles.

#include "formats/wfformat/workflow_json.hpp"

#include "formats/common/json_object.hpp"
#include "formats/common/json_text.hpp"
#include "formats/wfformat/cycle.hpp"
#include "formats/wfformat/readers.hpp"

#include <pagecache/error.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <array>

namespace pagecache::formats::wfformat {

namespace {

enum class Format { WfFormat15, WfFormat16, WrenchTasks };

// "1.5" is WfFormat 1.5, "1.6" the same with optional metrics. The old format has no
// schemaVersion (the WRENCH inputs) or an older one (WfFormat 1.3 and 1.4 have the same shape),
// and a workflow.tasks array. Anything else is refused by name rather than half-read.
Format detect_format(const JsonObject& root) {
  const nlohmann::json* version = root.find("schemaVersion");
  const nlohmann::json* workflow = root.find("workflow");
  const bool has_tasks = workflow != nullptr && workflow->is_object() && workflow->contains("tasks");
  if (version == nullptr) {
    if (has_tasks) return Format::WrenchTasks;
    root.fail("schemaVersion", "missing, and no workflow.tasks either: a WfFormat 1.5 file says \"schemaVersion\": \"1.5\", "
                               "the format before it lists workflow.tasks");
  }
  if (!version->is_string()) root.fail("schemaVersion", fmt::format("expected a string such as \"1.5\", got {}", a_type(*version)));
  const std::string& v = version->get_ref<const std::string&>();
  if (v == "1.5") return Format::WfFormat15;
  if (v == "1.6") return Format::WfFormat16;
  static constexpr std::array<std::string_view, 5> kOlder = {"1.0", "1.1", "1.2", "1.3", "1.4"};
  if (std::find(kOlder.begin(), kOlder.end(), v) == kOlder.end()) {
    root.fail("schemaVersion", fmt::format("{} is not a version this reader knows: it reads WfFormat 1.5 and 1.6, and the format before it "
                                           "(workflow.tasks, with no schemaVersion or 1.0 to 1.4)",
                                           quote_name(v)));
  }
  if (!has_tasks) {
    root.fail("schemaVersion", fmt::format("{} files list their tasks in workflow.tasks, and this one has none{}", quote_name(v),
                                           v < "1.3" ? " (1.0 to 1.2 wrote workflow.jobs: WfFormat's tools/wfcommons-migrate-instance.py "
                                                       "brings them to 1.5)"
                                                     : ""));
  }
  return Format::WrenchTasks;
}

std::string cycle_text(const std::vector<WfTask>& tasks, const std::vector<std::size_t>& cycle) {
  constexpr std::size_t kShown = 8;  // a cycle through 10^4 tasks is named by its start
  std::string out;
  for (std::size_t k = 0; k < cycle.size() && k < kShown; ++k) out += quote_name(tasks[cycle[k]].id) + " -> ";
  if (cycle.size() > kShown) out += fmt::format("... ({} tasks in all) -> ", cycle.size());
  return out + quote_name(tasks[cycle.front()].id);
}

}  // namespace

WfWorkflow read_workflow_json(const std::string& text, const std::string& file, std::int64_t max_tasks, std::int64_t max_files) {
  const nlohmann::json document = parse_json_text(text, file);
  if (!document.is_object()) {
    throw ConfigError(fmt::format("{}: expected a JSON object (a workflow instance) at the top level, got {}", file, a_type(document)));
  }
  const JsonObject root(document, "", file);
  WfWorkflow out;
  out.file = file;
  out.name = root.optional_string("name").value_or("");
  Warnings warnings(out);
  const WorkflowLimits limits{max_tasks, max_files};
  std::string tasks_path;
  const Format format = detect_format(root);
  if (format == Format::WfFormat15 || format == Format::WfFormat16) {
    out.format = format == Format::WfFormat15 ? "WfFormat 1.5" : "WfFormat 1.6";
    tasks_path = read_wfformat_15(root, limits, out, warnings);
  } else {
    out.format = "WRENCH 2.x (schema before 1.5)";
    tasks_path = read_wrench_tasks(root, limits, out, warnings);
  }
  if (const std::vector<std::size_t> cycle = find_cycle(out.tasks); !cycle.empty()) {
    const std::size_t first = cycle.front();
    throw ConfigError(fmt::format("{}: {}[{}] (task {}): parents: dependency cycle: {} (each task lists the next among its parents)", file,
                                  tasks_path, first, quote_name(out.tasks[first].id), cycle_text(out.tasks, cycle)));
  }
  // After the cycle check: the levels a 1.6 file states are those of an acyclic graph.
  if (format == Format::WfFormat16) check_wfformat_16_metrics(root, out, warnings);
  warnings.finish();
  return out;
}

}  // namespace pagecache::formats::wfformat
