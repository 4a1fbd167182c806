#include "scenario/workflow_speed.hpp"

#include <pagecache/error.hpp>

#include <fmt/format.h>

#include <cmath>
#include <unordered_map>

namespace pagecache::scenario {

using namespace formats::wfformat;  // the WfFormat reader's workflow

namespace {

// WRENCH's rule (WfCommonsWorkflowParser): a core of S MHz computes S x 10^6 flop/s.
constexpr double kFlopsPerMHz = 1e6;

// The flop/s the machines of the instance computed at, looked up by name.
class RecordedSpeeds {
 public:
  explicit RecordedSpeeds(const WfWorkflow& wf) : wf_(&wf) {
    for (std::size_t m = 0; m < wf.machines.size(); ++m) index_.emplace(wf.machines[m], m);
  }

  // The speed task `t` ran at, in flop/s.
  double of(const WfTask& t, std::optional<double> reference) const {
    const auto where = [&] { return fmt::format("{}: task '{}': machines", wf_->file, t.id); };
    std::optional<double> speed;
    std::string first;
    for (const std::string& name : t.machines) {
      const auto it = index_.find(name);
      if (it == index_.end()) {
        throw ConfigError(fmt::format("{}: '{}' is no machine of the instance's list, so its speed is unknown (compute = \"speed\")", where(),
                                      name));
      }
      const WfMachineSpeed& m = wf_->machine_speeds[it->second];
      if (m.mhz == -1) continue;  // not given: the reference speed, if any
      if (!(m.mhz > 0) || !std::isfinite(m.mhz)) {
        throw ConfigError(fmt::format("{}: must be a number of MHz > 0 for compute = \"speed\", got {}", m.place,
                                      std::isnan(m.mhz) ? std::string("no number") : fmt::format("{}", m.mhz)));
      }
      const double flops = m.mhz * kFlopsPerMHz;
      if (speed && *speed != flops) {
        throw ConfigError(fmt::format("{}: ran on '{}' ({} MHz) and '{}' ({} MHz): compute = \"speed\" needs one speed per task", where(), first,
                                      *speed / kFlopsPerMHz, name, m.mhz));
      }
      speed = flops;
      first = name;
    }
    if (speed) return *speed;
    if (reference) return *reference;
    throw ConfigError(fmt::format("{}: {}, so compute = \"speed\" has no speed to scale from: give reference_speed (the flop/s of the "
                                  "machine its runtime was measured on)",
                                  where(), t.machines.empty() ? "none recorded" : "the instance gives its machine no cpu speed"));
  }

 private:
  const WfWorkflow* wf_;
  std::unordered_map<std::string, std::size_t> index_;
};

}  // namespace

std::vector<double> speed_ratios(const WfWorkflow& wf, const std::vector<TaskSpec>& tasks, const std::vector<std::string>& hosts,
                                 std::optional<double> reference_speed, const Scenario& s, const Origins& origins,
                                 const std::function<void(const std::string&, const std::string&)>& fail) {
  std::unordered_map<std::string, std::size_t> host_index;
  for (std::size_t h = 0; h < s.hosts.size(); ++h) host_index.emplace(s.hosts[h].name, h);
  const auto speed_of = [&](const std::string& name) {
    const std::size_t h = host_index.at(name);  // the caller checked every host name
    const double speed = s.hosts[h].speed;
    if (speed > 0.0) return speed;
    const std::string message = "no speed, which compute = \"speed\" needs: give the host a speed in flop/s (\"1.2Gf\")";
    if (h < origins.hosts.size()) origins.hosts[h].fail("speed", message);
    throw ConfigError(fmt::format("host '{}': speed: {}", name, message));
  };
  // A task the run places itself goes to any of the workflow's hosts: they must agree.
  std::optional<double> shared;
  const auto shared_speed = [&] {
    if (shared) return *shared;
    for (const std::string& h : hosts) {
      const double speed = speed_of(h);
      if (shared && *shared != speed) {
        fail("hosts", fmt::format("hosts '{}' ({} flop/s) and '{}' ({} flop/s) differ in speed, and compute = \"speed\" scales a runtime "
                                  "before the run chooses its host: give hosts of one speed, or record each task's machine among them",
                                  hosts.front(), *shared, h, speed));
      }
      shared = speed;
    }
    return *shared;
  };
  const RecordedSpeeds recorded(wf);
  std::vector<double> ratios;
  ratios.reserve(tasks.size());
  for (std::size_t t = 0; t < tasks.size(); ++t) {
    const double host = tasks[t].host.empty() ? shared_speed() : speed_of(tasks[t].host);
    ratios.push_back(recorded.of(wf.tasks[t], reference_speed) / host);
  }
  return ratios;
}

}  // namespace pagecache::scenario
