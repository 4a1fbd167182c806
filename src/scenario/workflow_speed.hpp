#pragma once
// compute = "speed": a recorded runtime scaled from the machine that ran the task to the host
// that runs it in the simulation, as WRENCH's WfCommonsWorkflowParser does. A recorded machine
// of S MHz computes S x 10^6 flop/s (one flop per cycle, WRENCH's rule, which WfCommons'
// SimGrid platforms follow: a 1202 MHz machine is a host of speed "1.202Gf"), so a task that
// took T s there takes T x S x 10^6 / host speed here. A task that records no machine, or one
// whose machine gives no speed, is taken to have run at `reference_speed` (WRENCH's
// reference_flop_rate), if given.

#include <pagecache/scenario.hpp>

#include "scenario/origins.hpp"
#include "formats/wfformat/workflow_json.hpp"

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace pagecache::scenario {

/// Per task of `wf` (in its order), its recorded machine's speed over the speed of the host it
/// runs on: task i's own host if `tasks[i].host` names one, else the workflow's `hosts`, which
/// must then share one speed (the host is chosen at run time, the runtime scaled before).
/// Refused, with a ConfigError naming the file and key: a task naming a machine the instance
/// does not describe; a machine's speed that is no number or not > 0; a task that ran on
/// machines of different speeds; a task with no machine speed and no `reference_speed`; a
/// host without a speed (from `origins`); hosts of different speeds for an unplaced task
/// (`fail("hosts", ...)`).
std::vector<double> speed_ratios(const formats::wfformat::WfWorkflow& wf, const std::vector<TaskSpec>& tasks, const std::vector<std::string>& hosts,
                                 std::optional<double> reference_speed, const Scenario& s, const Origins& origins,
                                 const std::function<void(const std::string&, const std::string&)>& fail);

}  // namespace pagecache::scenario
