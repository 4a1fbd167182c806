#include "scenario/workflow_import.hpp"

#include <pagecache/error.hpp>

#include "scenario/toml_reader.hpp"
#include "scenario/workflow_speed.hpp"
#include "text/printable.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <set>
#include <string_view>
#include <unordered_map>
#include <utility>

namespace pagecache::scenario {

using namespace formats::wfformat;  // the WfFormat reader's workflow

namespace {

using Fail = std::function<void(const std::string&, const std::string&)>;

// The platform's hosts by name: an instance of 10^6 tasks on a cluster of 10^5 hosts must not
// scan them per task.
class HostIndex {
 public:
  explicit HostIndex(const Scenario& s) {
    for (const HostConfig& h : s.hosts) hosts_.emplace(h.name, &h);
  }
  const HostConfig* find(const std::string& name) const {
    const auto it = hosts_.find(name);
    return it == hosts_.end() ? nullptr : it->second;
  }

 private:
  std::unordered_map<std::string_view, const HostConfig*> hosts_;
};

// The recorded machines the platform has: the instance's list first, then the tasks' own.
std::vector<std::string> recorded_machines(const WfWorkflow& wf, const HostIndex& hosts) {
  std::vector<std::string> ordered;
  std::set<std::string_view> noted;
  const auto note_machine = [&](const std::string& m) {
    if (hosts.find(m) != nullptr && noted.insert(m).second) ordered.push_back(m);
  };
  for (const std::string& m : wf.machines) note_machine(m);
  for (const WfTask& t : wf.tasks) {
    for (const std::string& m : t.machines) note_machine(m);
  }
  return ordered;
}

// Where the workflow's files are stored: the files host and its disk.
std::pair<std::string, std::string> files_place(const WorkflowImport& o, const std::vector<std::string>& ordered, const Scenario& s,
                                                const HostIndex& hosts, const Fail& fail) {
  const std::string files_host = !o.files_host.empty() ? o.files_host
                                 : !ordered.empty()      ? ordered.front()
                                 : !o.hosts.empty()      ? o.hosts.front()
                                                         : s.hosts.front().name;
  const HostConfig* store = hosts.find(files_host);
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
  return {files_host, files_disk};
}

// The instance's task and file ids, each able to name one (name_problem).
void check_names(const WfWorkflow& wf) {
  for (const WfTask& t : wf.tasks) {
    if (const std::string problem = formats::name_problem(t.id); !problem.empty()) {
      throw ConfigError(fmt::format("{}: task '{}': {}", wf.file, text::printable(t.id), problem));
    }
  }
  for (const WfFile& f : wf.files) {
    if (const std::string problem = formats::name_problem(f.id); !problem.empty()) {
      throw ConfigError(fmt::format("{}: file '{}': {}", wf.file, text::printable(f.id), problem));
    }
  }
}

// The hosts the workflow's tasks may run on (WorkflowImport::hosts says which).
std::vector<std::string> workflow_hosts(const WorkflowImport& o, const std::vector<std::string>& ordered, const std::string& files_host,
                                        const Scenario& s, const HostIndex& hosts, const Fail& fail) {
  std::vector<std::string> chosen;
  if (!o.hosts.empty()) {
    for (const std::string& h : o.hosts) {
      if (hosts.find(h) == nullptr) fail("hosts", fmt::format("no host named '{}'", h));
    }
    chosen = o.hosts;
  } else if (!ordered.empty()) {
    chosen = ordered;
  } else if (!o.files_host.empty()) {
    // A files host chosen, no machine recorded: a storage server, the others compute.
    for (const HostConfig& h : s.hosts) {
      if (h.name != files_host) chosen.push_back(h.name);
    }
    if (chosen.empty()) chosen.push_back(files_host);
  } else {
    chosen.push_back(files_host);  // everything on one host, on its local disk
  }
  return chosen;
}

// The instance's files, all on the files host; those no task writes start cached if asked.
void add_files(const WfWorkflow& wf, const WorkflowImport& o, const std::string& files_host, const std::string& files_disk, Scenario& s,
               Origins& origins) {
  std::vector<bool> written(wf.files.size(), false);
  for (const WfTask& t : wf.tasks) {
    for (const std::size_t f : t.outputs) written[f] = true;
  }
  const std::string json = wf.file;
  for (std::size_t f = 0; f < wf.files.size(); ++f) {
    s.files.push_back({wf.files[f].id, wf.files[f].size, files_host, files_disk, o.inputs_cached && !written[f]});
    origins.files.push_back(Origin::elsewhere(fmt::format("{}: file '{}'", json, wf.files[f].id)));
  }
}

// The instance's tasks, each on the first of its recorded machines the platform has, if any.
void add_tasks(const WfWorkflow& wf, const WorkflowImport& o, const HostIndex& hosts, WorkflowSpec& w, Origins& origins) {
  const std::string json = wf.file;
  std::vector<Origin>& task_origins = origins.workflow_tasks.emplace_back();
  w.tasks.reserve(wf.tasks.size());
  for (const WfTask& t : wf.tasks) {
    TaskSpec& task = w.tasks.emplace_back();
    task.name = t.id;
    for (const std::string& m : t.machines) {
      if (hosts.find(m) != nullptr) {
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
}

}  // namespace

void add_json_workflow(const WfWorkflow& wf, const WorkflowImport& o, Scenario& s, Origins& origins, const Fail& fail) {
  const HostIndex hosts(s);
  const std::vector<std::string> ordered = recorded_machines(wf, hosts);
  const auto [files_host, files_disk] = files_place(o, ordered, s, hosts, fail);
  check_names(wf);

  s.warnings.insert(s.warnings.end(), wf.warnings.begin(), wf.warnings.end());
  WorkflowSpec w;
  w.name = o.name.empty() ? (wf.name.empty() ? std::string("workflow") : wf.name) : o.name;
  w.source = wf.file;
  w.hosts = workflow_hosts(o, ordered, files_host, s, hosts, fail);
  add_files(wf, o, files_host, files_disk, s, origins);
  add_tasks(wf, o, hosts, w, origins);
  if (o.compute == ComputeFrom::Speed) {
    const std::vector<double> ratios = speed_ratios(wf, w.tasks, w.hosts, o.reference_speed, s, origins, fail);
    for (std::size_t t = 0; t < w.tasks.size(); ++t) w.tasks[t].compute = wf.tasks[t].runtime * ratios[t];
  }
  s.workflows.push_back(std::move(w));
}

}  // namespace pagecache::scenario
