#pragma once
// The two readers behind read_workflow_json, one per format.

#include "formats/common/json_object.hpp"
#include "formats/wfformat/workflow_json.hpp"
#include "formats/wfformat/links.hpp"

#include <cstdint>
#include <string>

namespace pagecache::formats::wfformat {

struct WorkflowLimits {
  std::int64_t max_tasks = 0;
  std::int64_t max_files = 0;
};

/// Reads the WfFormat 1.5 (or 1.6) instance `root` into `out`: specification (tasks, files, references)
/// and execution (runtimes, cores, memory, machines). Returns the path of the task array, for
/// messages about the graph as a whole.
std::string read_wfformat_15(const JsonObject& root, const WorkflowLimits& limits, WfWorkflow& out, Warnings& warnings);

/// Reads the format before WfFormat 1.5 (WRENCH 2.x's inputs; WfFormat 1.3 and 1.4) into
/// `out`. Returns the path of the task array.
std::string read_wrench_tasks(const JsonObject& root, const WorkflowLimits& limits, WfWorkflow& out, Warnings& warnings);

/// Checks the figures a WfFormat 1.6 instance `root` states about its workflow (the optional
/// workflow.specification.metrics and workflow.execution.metrics) against `wf`, read from it and
/// acyclic: a figure of the wrong kind (not a non-negative number; a fraction where 1.6 wants a
/// whole one) is a ConfigError naming the file, path and key; one that disagrees, a warning
/// naming both numbers.
void check_wfformat_16_metrics(const JsonObject& root, const WfWorkflow& wf, Warnings& warnings);

/// The percentage avgCPU may reach: 100 per core.
inline constexpr double kMaxAvgCpu = 100.0 * static_cast<double>(kMaxCores);

}  // namespace pagecache::formats::wfformat
