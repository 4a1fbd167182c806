// The check that every host a task may run on reaches the files the task names, over a route
// that fits in a flow. Each pair of hosts is looked at once: a workflow's tasks may run on
// every host of a cluster.

#include "scenario/loader_sections.hpp"

#include <pagecache/error.hpp>
#include <pagecache/fair_share.hpp>

#include "estimate/route_index.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace pagecache::scenario {

using namespace estimate;  // the pre-run estimate's route index

namespace {

class ReachCheck {
 public:
  ReachCheck(const Scenario& s, const std::map<std::string, const FileSpec*>& files) : routes_(s), files_(files) {
    for (const HostConfig& h : s.hosts) host_names_.insert(h.name);
    for (const FileSetSpec& set : s.file_sets) set_hosts_.emplace(set.name, &set.host);
  }

  // The tasks of `owner` (an application or a workflow), which may run on any of `hosts`.
  // `where`: the file the tasks were read from, named in messages (a workflow file's own).
  void tasks(const std::string& where, const std::string& owner, const std::vector<std::string>& hosts, const std::vector<TaskSpec>& tasks) {
    for (const std::string& host : hosts) {
      if (host_names_.count(host) == 0) throw ConfigError(fmt::format("{}: {}: no host named '{}'", where, owner, host));
    }
    // The hosts storing the files of the tasks that may run on any of `hosts`: (task, file) first
    // needing each, checked against every such host after.
    std::map<std::string, std::pair<const std::string*, const std::string*>> servers;
    for (const TaskSpec& t : tasks) {
      if (!t.host.empty() && host_names_.count(t.host) == 0) {
        throw ConfigError(fmt::format("{}: {}, task '{}': no host named '{}'", where, owner, t.name, t.host));
      }
      for (const auto* list : {&t.reads, &t.writes, &t.deletes}) {
        for (const std::string& name : *list) {
          auto it = files_.find(name);
          if (it == files_.end()) throw ConfigError(fmt::format("{}: {}, task '{}': unknown file '{}'", where, owner, t.name, name));
          const std::string& server = it->second->host;
          if (!t.host.empty()) reach(where, owner, t.name, name, t.host, server);
          else servers.try_emplace(server, &t.name, &it->first);
        }
      }
      for (const AccessSpec& a : t.accesses) {
        if (!a.file.empty()) {
          local(where, owner, t, a.file, t.host.empty() ? hosts : std::vector<std::string>{t.host});
          continue;
        }
        const auto it = set_hosts_.find(a.file_set);
        if (it == set_hosts_.end()) throw ConfigError(fmt::format("{}: {}, task '{}': unknown file set '{}'", where, owner, t.name, a.file_set));
        if (!t.host.empty()) reach(where, owner, t.name, a.file_set, t.host, *it->second);
        else servers.try_emplace(*it->second, &t.name, &it->first);
      }
    }
    for (const auto& [server, first] : servers) {
      for (const std::string& host : hosts) reach(where, owner, *first.first, *first.second, host, server);
    }
  }

 private:
  // Reads and writes by part (Host::read_ranges) are of a file of the task's own host: one it
  // might read over a route is refused.
  void local(const std::string& where, const std::string& owner, const TaskSpec& t, const std::string& file_name,
             const std::vector<std::string>& hosts) {
    const auto it = files_.find(file_name);
    if (it == files_.end()) throw ConfigError(fmt::format("{}: {}, task '{}': unknown file '{}'", where, owner, t.name, file_name));
    const std::string& server = it->second->host;
    for (const std::string& host : hosts) {
      if (host != server) {
        throw ConfigError(fmt::format("{}: {}, task '{}': file '{}' is on host '{}' and the task may run on '{}': an access of parts of a "
                                      "file (file = \"{}\") is of a file of the task's own host (pcsim does not model reads by part over "
                                      "the network)",
                                      where, owner, t.name, file_name, server, host, file_name));
      }
    }
  }

  void reach(const std::string& where, const std::string& owner, const std::string& task, const std::string& file_name, const std::string& host,
             const std::string& server) {
    if (server == host || !reachable_.emplace(host, server).second) return;
    const std::vector<const LinkSpec*>& route = routes_.between(host, server);
    if (route.empty()) {
      throw ConfigError(fmt::format("{}: {}, task '{}': file '{}' is on host '{}', and no link or route joins it to '{}'", where, owner,
                                    task, file_name, server, host));
    }
    // A transfer is one flow through its route's shared links, the two memories and a disk
    // (devices.hpp): kMaxResourcesPerFlow in all.
    const auto shared = std::count_if(route.begin(), route.end(), [](const LinkSpec* l) { return l->sharing == pagecache::LinkSharing::Shared; });
    if (static_cast<std::size_t>(shared) + 2 > kMaxResourcesPerFlow) {
      throw ConfigError(fmt::format("{}: {}, task '{}': the route from '{}' to '{}' crosses {} shared links; pcsim models routes of at most {}",
                                    where, owner, task, host, server, shared, kMaxResourcesPerFlow - 2));
    }
  }

  const RouteIndex routes_;
  const std::map<std::string, const FileSpec*>& files_;
  std::set<std::string> host_names_;
  std::map<std::string, const std::string*> set_hosts_;  // file set -> the host storing it
  std::set<std::pair<std::string, std::string>> reachable_;  // (host, server) pairs already checked
};

}  // namespace

void check_reach(const Scenario& s, const std::string& file, const std::map<std::string, const FileSpec*>& files) {
  ReachCheck check(s, files);
  for (const AppSpec& a : s.apps) check.tasks(file, "application '" + a.name + "'", {a.host}, a.tasks);
  for (const WorkflowSpec& w : s.workflows) check.tasks(w.source.empty() ? file : w.source, "workflow '" + w.name + "'", w.hosts, w.tasks);
}

}  // namespace pagecache::scenario
