#include "scenario/workflow_import.hpp"

#include <pagecache/error.hpp>

#include "scenario/toml_reader.hpp"
#include "text/printable.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <set>
#include <string_view>
#include <unordered_map>

namespace pagecache::scenario {

namespace {

}  // namespace

void add_json_workflow(const WfWorkflow& wf, const WorkflowImport& o, Scenario& s, Origins& origins,
                       const std::function<void(const std::string&, const std::string&)>& fail) {
  // By name: an instance of 10^6 tasks on a cluster of 10^5 hosts must not scan them per task.
  std::unordered_map<std::string_view, const HostConfig*> hosts;
  for (const HostConfig& h : s.hosts) hosts.emplace(h.name, &h);
  const auto host_named = [&](const Scenario&, const std::string& name) -> const HostConfig* {
    const auto it = hosts.find(name);
    return it == hosts.end() ? nullptr : it->second;
  };
  // The recorded machines the platform has: the instance's list first, then the tasks' own.
  std::vector<std::string> ordered;
  std::set<std::string_view> noted;
  const auto note_machine = [&](const std::string& m) {
    if (host_named(s, m) != nullptr && noted.insert(m).second) ordered.push_back(m);
  };
  for (const std::string& m : wf.machines) note_machine(m);
  for (const WfTask& t : wf.tasks) {
    for (const std::string& m : t.machines) note_machine(m);
  }

  const std::string files_host = !o.files_host.empty() ? o.files_host
                                 : !ordered.empty()      ? ordered.front()
                                 : !o.hosts.empty()      ? o.hosts.front()
                                                         : s.hosts.front().name;
  const HostConfig* store = host_named(s, files_host);
  if (store == nullptr) fail("files_host", fmt::format("no host named '{}'", files_host));
  std::string files_disk = o.files_disk;
  if (files_disk.empty()) {
    if (store->disks.empty()) {
      fail("files_host", fmt::format("host '{}' has no disk to store the workflow's files (give one, or choose another files_host)", files_host));
    }
    files_disk = store->disks.front().name;
  } else if (std::none_of(store->disks.begin(), store->disks.end(), [&](const DiskSpec& d) { return d.name == files_disk; })) {
    fail("files_disk", fmt::format("host '{}' has no disk named '{}'", files_host, files_disk));
  }

  for (const WfTask& t : wf.tasks) {
    if (const std::string problem = name_problem(t.id); !problem.empty()) {
      throw ConfigError(fmt::format("{}: task '{}': {}", wf.file, text::printable(t.id), problem));
    }
  }
  for (const WfFile& f : wf.files) {
    if (const std::string problem = name_problem(f.id); !problem.empty()) {
      throw ConfigError(fmt::format("{}: file '{}': {}", wf.file, text::printable(f.id), problem));
    }
  }

  s.warnings.insert(s.warnings.end(), wf.warnings.begin(), wf.warnings.end());
  WorkflowSpec w;
  w.name = o.name.empty() ? (wf.name.empty() ? std::string("workflow") : wf.name) : o.name;
  w.source = wf.file;
  if (!o.hosts.empty()) {
    for (const std::string& h : o.hosts) {
      if (host_named(s, h) == nullptr) fail("hosts", fmt::format("no host named '{}'", h));
    }
    w.hosts = o.hosts;
  } else if (!ordered.empty()) {
    w.hosts = ordered;
  } else if (!o.files_host.empty()) {
    // A files host chosen, no machine recorded: a storage server, the others compute.
    for (const HostConfig& h : s.hosts) {
      if (h.name != files_host) w.hosts.push_back(h.name);
    }
    if (w.hosts.empty()) w.hosts.push_back(files_host);
  } else {
    w.hosts.push_back(files_host);  // everything on one host, on its local disk
  }

  std::vector<bool> written(wf.files.size(), false);
  for (const WfTask& t : wf.tasks) {
    for (const std::size_t f : t.outputs) written[f] = true;
  }
  const std::string json = wf.file;
  for (std::size_t f = 0; f < wf.files.size(); ++f) {
    s.files.push_back({wf.files[f].id, wf.files[f].size, files_host, files_disk, o.inputs_cached && !written[f]});
    origins.files.push_back(Origin::elsewhere(fmt::format("{}: file '{}'", json, wf.files[f].id)));
  }

  std::vector<Origin>& task_origins = origins.workflow_tasks.emplace_back();
  w.tasks.reserve(wf.tasks.size());
  for (const WfTask& t : wf.tasks) {
    TaskSpec& task = w.tasks.emplace_back();
    task.name = t.id;
    for (const std::string& m : t.machines) {
      if (host_named(s, m) != nullptr) {
        task.host = m;
        break;
      }
    }
    task.cores = t.cores;
    task.memory = t.memory;
    for (const std::size_t f : t.inputs) task.reads.push_back(wf.files[f].id);
    for (const std::size_t f : t.outputs) task.writes.push_back(wf.files[f].id);
    for (const std::size_t p : t.parents) task.after.push_back(wf.tasks[p].id);
    task.compute = t.runtime;
    if (o.compute == ComputeFrom::CpuShare && t.avg_cpu >= 0.0) {
      task.compute = t.runtime * std::min(1.0, t.avg_cpu / 100.0 / static_cast<double>(t.cores));
    }
    task.chunk_size = o.chunk_size;
    task.memory_limits = o.memory_limits;
    task_origins.push_back(Origin::elsewhere(fmt::format("{}: task '{}'", json, t.id)));
  }
  s.workflows.push_back(std::move(w));
}

}  // namespace pagecache::scenario
