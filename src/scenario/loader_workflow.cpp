// The workflow of a scenario: a WfFormat instance (workflow = "x.json", or [workflow] with
// file = "x.json" and the options of its import), or a [workflow] table with its
// [[workflow.tasks]]; and the checks of a workflow's tasks: no dependency cycle, no task
// needing more cores than its hosts have.

#include "scenario/loader_sections.hpp"

#include <pagecache/error.hpp>

#include "formats/common/text_file.hpp"
#include "scenario/workflow_import.hpp"
#include "formats/wfformat/workflow_json.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <string_view>
#include <unordered_map>

namespace pagecache::scenario {

using namespace formats::wfformat;  // the WfFormat reader's workflow

namespace {

// A cycle of dependencies, reported with its tasks. Iterative: a workflow may be a chain of
// 10^5 tasks, deeper than the stack a recursive search would need. `tasks`: where each task
// is; a workflow file's (JSON) are named there, its tasks having no TOML table.
void check_workflow_acyclic(const WorkflowSpec& w, const Origin& r, const std::vector<Origin>& tasks) {
  std::map<std::string, std::size_t> by_name;
  std::map<std::string, std::size_t> producer;
  for (std::size_t i = 0; i < w.tasks.size(); ++i) {
    if (!by_name.emplace(w.tasks[i].name, i).second) r.fail("tasks", fmt::format("two tasks named '{}'", w.tasks[i].name));
    for (const auto& f : w.tasks[i].writes) {
      const auto [first, added] = producer.emplace(f, i);
      if (added) continue;
      if (!w.source.empty()) {
        tasks[i].fail_table(fmt::format("file '{}' is written by two tasks, '{}' and '{}'", f, w.tasks[first->second].name, w.tasks[i].name));
      }
      r.fail("tasks", fmt::format("file '{}' is written by two tasks", f));
    }
  }
  std::vector<std::vector<std::size_t>> deps(w.tasks.size());
  for (std::size_t i = 0; i < w.tasks.size(); ++i) {
    for (const auto& a : w.tasks[i].after) {
      auto it = by_name.find(a);
      if (it == by_name.end()) r.fail("tasks", fmt::format("task '{}' comes after an unknown task '{}'", w.tasks[i].name, a));
      deps[i].push_back(it->second);
    }
    for (const auto& f : w.tasks[i].reads) {
      if (auto it = producer.find(f); it != producer.end()) deps[i].push_back(it->second);
    }
  }
  enum : char { Unseen, OnPath, Done };
  std::vector<char> state(w.tasks.size(), Unseen);
  std::vector<std::pair<std::size_t, std::size_t>> path;  // (task, next dependency to visit)
  for (std::size_t root = 0; root < w.tasks.size(); ++root) {
    if (state[root] != Unseen) continue;
    state[root] = OnPath;
    path.emplace_back(root, 0);
    while (!path.empty()) {
      auto& [task, next] = path.back();
      if (next == deps[task].size()) {
        state[task] = Done;
        path.pop_back();
        continue;
      }
      const std::size_t d = deps[task][next++];
      if (state[d] == OnPath) {
        std::string cycle;
        auto it = std::find_if(path.begin(), path.end(), [&](const auto& p) { return p.first == d; });
        for (; it != path.end(); ++it) cycle += w.tasks[it->first].name + " -> ";
        r.fail("tasks", fmt::format("dependency cycle: {}{}", cycle, w.tasks[d].name));
      }
      if (state[d] == Unseen) {
        state[d] = OnPath;
        path.emplace_back(d, 0);
      }
    }
  }
}

// The options of a workflow file's import: the keys of its [workflow] table other than `file`.
WorkflowImport read_import_options(TomlReader& table) {
  WorkflowImport options;
  options.name = table.name("name", "");
  options.files_host = table.name("files_host", "");
  options.files_disk = table.name("files_disk", "");
  options.hosts = table.names("hosts");
  if (table.has("hosts") && options.hosts.empty()) table.fail("hosts", "at least one host");
  options.inputs_cached = table.optional_bool("inputs_cached").value_or(false);
  if (auto compute = table.optional_string("compute")) {
    if (*compute == "runtime") options.compute = ComputeFrom::Runtime;
    else if (*compute == "cpu_share") options.compute = ComputeFrom::CpuShare;
    else if (*compute == "speed") options.compute = ComputeFrom::Speed;
    else table.fail("compute", fmt::format("unknown '{}' (use \"runtime\", \"cpu_share\" or \"speed\")", *compute));
  }
  options.reference_speed = read_speed(table, "reference_speed");
  if (options.reference_speed && options.compute != ComputeFrom::Speed) {
    table.fail("reference_speed", "is read by compute = \"speed\" alone");
  }
  options.chunk_size = table.optional_size("chunk_size").value_or(options.chunk_size);
  if (options.chunk_size <= 0) table.fail("chunk_size", "must be > 0");
  options.memory_limits = read_memory_limits(table, "each task's");
  return options;
}

// workflow = "x.json", or [workflow] with file = "x.json": a workflow instance and its options.
void read_workflow_file(TomlReader& root, Scenario& s, const std::string& file, const ScenarioLimits& limits, Origins& origins) {
  const toml::node* node = root.raw("workflow");
  WorkflowImport options;
  std::string path;
  std::optional<TomlReader> table;
  if (node->is_string()) {
    path = *node->value<std::string>();
    origins.workflows.push_back(origins.root);
  } else {
    table.emplace(*node->as_table(), "workflow", file);
    origins.workflows.push_back({node->as_table(), "workflow", &file});
    path = table->required_string("file");
    options = read_import_options(*table);
  }
  const std::string json = relative_path(file, path);
  const auto fail = [&](const std::string& key, const std::string& message) {
    // Not given, and the table has no place in a file (pcsim's options made it: load_workflow):
    // the workflow file decided it.
    if (table && !table->has(key) && node->source().begin.line == 0) throw ConfigError(fmt::format("{}: {}", json, message));
    if (table) table->fail(key, message);
    root.fail("workflow", message);
  };
  std::string text;
  try {
    text = formats::read_text_file(json, "workflow file");
  } catch (const ConfigError& e) {
    if (table) table->fail("file", e.what());
    root.fail("workflow", e.what());
  }
  const WfWorkflow workflow = read_workflow_json(text, json, limits.max_tasks, limits.max_files);
  add_json_workflow(workflow, options, s, origins, fail);
  if (table) table->finish();
  check_workflow_acyclic(s.workflows.back(), origins.workflows.back(), origins.workflow_tasks.back());
}

}  // namespace

void read_json_workflow(TomlReader& r, const std::string& file, const ScenarioLimits& limits, Scenario& s, Origins& origins) {
  const toml::node* workflow_node = r.table().get("workflow");
  const toml::table* workflow_table = workflow_node != nullptr ? workflow_node->as_table() : nullptr;
  if (workflow_node != nullptr && (workflow_node->is_string() || (workflow_table != nullptr && workflow_table->contains("file")))) {
    read_workflow_file(r, s, file, limits, origins);
  }
}

void read_workflow(TomlReader& r, const std::string& file, Scenario& s, Origins& origins) {
  if (const toml::table* w = s.workflows.empty() ? r.optional_table("workflow") : nullptr) {
    TomlReader wr(*w, "workflow", file);
    origins.workflows.push_back({w, "workflow", &file});
    std::vector<Origin>& task_origins = origins.workflow_tasks.emplace_back();
    WorkflowSpec workflow;
    workflow.name = wr.name("name", "workflow");
    if (wr.has("hosts")) {
      workflow.hosts = wr.names("hosts");
      if (workflow.hosts.empty()) wr.fail("hosts", "at least one host");
      if (wr.has("host")) wr.fail("host", "give either host or hosts");
    } else {
      workflow.hosts = {wr.name("host", s.hosts.front().name)};
    }
    for (const std::string& h : workflow.hosts) {
      if (std::none_of(s.hosts.begin(), s.hosts.end(), [&](const HostConfig& c) { return c.name == h; })) {
        wr.fail(wr.has("hosts") ? "hosts" : "host", fmt::format("no host named '{}'", h));
      }
    }
    const std::int64_t chunk = wr.optional_size("chunk_size").value_or(100'000'000);
    if (chunk <= 0) wr.fail("chunk_size", "must be > 0");
    const MemoryLimits memory_limits = read_memory_limits(wr, "each task's");
    const auto tasks = wr.tables("tasks");
    if (tasks.empty()) wr.fail_table("a workflow needs at least one [[workflow.tasks]]");
    AccessTargets targets(s);
    for (std::size_t t = 0; t < tasks.size(); ++t) {
      task_origins.push_back({tasks[t], wr.child_path("tasks", t), &file});
      workflow.tasks.push_back(read_task(*tasks[t], wr.child_path("tasks", t), t, chunk, file, targets, true, memory_limits));
    }
    check_workflow_acyclic(workflow, origins.workflows.back(), task_origins);
    wr.finish();
    s.workflows.push_back(std::move(workflow));
  }
}

void check_workflow_cores(const Scenario& s, const Origins& origins) {
  std::unordered_map<std::string_view, const HostConfig*> host_by_name;
  for (const HostConfig& h : s.hosts) host_by_name.emplace(h.name, &h);
  // A workflow task needing more cores than any host it may run on has would wait for ever.
  for (std::size_t w = 0; w < s.workflows.size(); ++w) {
    const WorkflowSpec& flow = s.workflows[w];
    int most = 0;
    for (const std::string& h : flow.hosts) most = std::max(most, host_by_name.at(h)->cores);
    for (std::size_t t = 0; t < flow.tasks.size(); ++t) {
      const TaskSpec& task = flow.tasks[t];
      const int cores = task.host.empty() ? most : host_by_name.at(task.host)->cores;
      if (task.cores <= cores) continue;
      const std::string message = fmt::format("needs {} cores, more than {} has ({})", task.cores,
                                              task.host.empty() ? "any of its workflow's hosts" : fmt::format("its host '{}'", task.host), cores);
      // A workflow file's task is named by its place.
      if (flow.source.empty()) origins.workflow_tasks[w][t].fail("cores", fmt::format("task '{}': {}", task.name, message));
      origins.workflow_tasks[w][t].fail_table(message);
    }
  }
}

}  // namespace pagecache::scenario
