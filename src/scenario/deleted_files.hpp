#pragma once
// Reads of deleted files whose order the scenario fixes: a task of an application reading a
// file that an earlier task of it deleted (and none wrote again since), or a workflow task
// reading a file that a task it runs after deleted. Those the run's order decides (tasks of
// different applications, workflow tasks in no fixed order) are the run's to refuse
// (run_scenario throws a SimulationError naming the simulated time).

#include <pagecache/scenario.hpp>

#include "scenario/origins.hpp"

namespace pagecache::scenario {

/// Throws ConfigError naming the reading task, the file and the task that deleted it, at the
/// reading task's `read` key.
void check_reads_of_deleted_files(const Scenario& s, const Origins& origins);

}  // namespace pagecache::scenario
