#pragma once
// Dependency cycles among a workflow's tasks, found by an iterative depth-first search: a
// chain of 10^6 tasks needs no deeper call stack than one task.

#include "formats/wfformat/workflow_json.hpp"

#include <cstddef>
#include <vector>

namespace pagecache::formats::wfformat {

/// A cycle of `tasks` along their parents: each task lists the next among its parents, and the
/// last lists the first. Empty if there is none.
std::vector<std::size_t> find_cycle(const std::vector<WfTask>& tasks);

}  // namespace pagecache::formats::wfformat
