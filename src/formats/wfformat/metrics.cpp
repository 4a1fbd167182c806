// WfFormat 1.6's figures about the workflow (WfFormat README, "What's New in 1.6"):
// workflow.specification.metrics (numberOfTasks, numberOfFiles, sumOfFileSizesInBytes,
// numberOfLevels, minimumWidth, maximumWidth) and workflow.execution.metrics
// (sumTaskRuntimesInSeconds, totalNumBytesRead, totalNumBytesWritten), all optional. Each is
// recomputed from the workflow as WfFormat's validator recomputes it; one that disagrees is a
// warning naming both numbers (the workflow itself is what pcsim runs), a malformed one an error.

#include "formats/wfformat/readers.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <string_view>

namespace pagecache::formats::wfformat {

namespace {

// WfFormat's validator compares with math.isclose(rel_tol=1e-9): a sum of runtimes written
// with fewer digits than a double holds still agrees.
constexpr double kRelativeTolerance = 1e-9;

bool close(double declared, double computed) {
  return std::abs(declared - computed) <= kRelativeTolerance * std::max(std::abs(declared), std::abs(computed));
}

// The widths of the DAG's levels: a task without parents is at level 0, any other one level
// below its deepest parent (Kahn's order, one level at a time). The graph is acyclic here.
std::vector<std::int64_t> level_widths(const std::vector<WfTask>& tasks) {
  std::vector<std::size_t> waiting(tasks.size());
  std::vector<std::vector<std::size_t>> children(tasks.size());
  std::deque<std::size_t> ready;
  for (std::size_t t = 0; t < tasks.size(); ++t) {
    waiting[t] = tasks[t].parents.size();
    for (const std::size_t p : tasks[t].parents) children[p].push_back(t);
    if (waiting[t] == 0) ready.push_back(t);
  }
  std::vector<std::int64_t> widths;
  while (!ready.empty()) {
    const std::size_t width = ready.size();
    widths.push_back(static_cast<std::int64_t>(width));
    for (std::size_t k = 0; k < width; ++k) {
      const std::size_t t = ready.front();
      ready.pop_front();
      for (const std::size_t c : children[t]) {
        if (--waiting[c] == 0) ready.push_back(c);
      }
    }
  }
  return widths;
}

struct Figure {
  std::string_view key;
  double computed;
  std::string_view what;  // what the workflow's number counts, for the warning
  bool whole;             // a non-negative integer in WfFormat 1.6; else a non-negative number
};

void compare(const JsonObject& metrics, const std::vector<Figure>& figures, Warnings& warnings) {
  constexpr std::int64_t kMostWhole = std::int64_t{1} << 62;  // beyond: no figure a workflow pcsim reads can have
  for (const Figure& f : figures) {
    double declared = 0;
    if (f.whole) {
      const std::optional<std::int64_t> v = metrics.optional_whole(f.key, 0, kMostWhole);
      if (!v) continue;
      declared = static_cast<double>(*v);
    } else {
      const std::optional<double> v = metrics.optional_number(f.key, 0, std::numeric_limits<double>::max());
      if (!v) continue;
      declared = *v;
    }
    if (close(declared, f.computed)) continue;
    warnings.add(metrics.message(f.key, fmt::format("declares {}, but the workflow gives {} ({}); the figure is ignored", declared,
                                                    f.computed, f.what)));
  }
}

// The sum of a number every execution record may carry (readBytes, writtenBytes), as WfFormat's
// validator sums it: the records that have it. The reader ignores these keys, so a value that
// is no number is skipped here too (1.6 reads as 1.5 does).
double sum_of_records(const nlohmann::json::array_t& records, std::string_view key) {
  double sum = 0;
  for (const nlohmann::json& r : records) {
    const auto it = r.find(key);
    if (it != r.end() && it->is_number()) sum += it->get<double>();
  }
  return sum;
}

}  // namespace

void check_wfformat_16_metrics(const JsonObject& root, const WfWorkflow& wf, Warnings& warnings) {
  const JsonObject workflow = root.required_object("workflow", "");
  const JsonObject spec = workflow.required_object("specification", "");
  if (const std::optional<JsonObject> metrics = spec.optional_object("metrics")) {
    double bytes = 0;
    for (const WfFile& f : wf.files) bytes += static_cast<double>(f.size);
    const std::vector<std::int64_t> widths = level_widths(wf.tasks);
    const auto [narrowest, widest] = std::minmax_element(widths.begin(), widths.end());  // a workflow has a task, hence a level
    compare(*metrics,
            {{"numberOfTasks", static_cast<double>(wf.tasks.size()), "tasks in workflow.specification.tasks", true},
             {"numberOfFiles", static_cast<double>(wf.files.size()), "files in workflow.specification.files", true},
             {"sumOfFileSizesInBytes", bytes, "the sum of the files' sizeInBytes", true},
             {"numberOfLevels", static_cast<double>(widths.size()), "levels of the task graph", true},
             {"minimumWidth", static_cast<double>(*narrowest), "tasks in the narrowest level", true},
             {"maximumWidth", static_cast<double>(*widest), "tasks in the widest level", true}},
            warnings);
  }
  const std::optional<JsonObject> execution = workflow.optional_object("execution");
  if (!execution) return;
  if (const std::optional<JsonObject> metrics = execution->optional_object("metrics")) {
    const nlohmann::json::array_t& records = execution->required_array("tasks", "");
    compare(*metrics,
            {{"sumTaskRuntimesInSeconds", sum_of_records(records, "runtimeInSeconds"), "the sum of the tasks' runtimeInSeconds", false},
             {"totalNumBytesRead", sum_of_records(records, "readBytes"), "the sum of the tasks' readBytes", true},
             {"totalNumBytesWritten", sum_of_records(records, "writtenBytes"), "the sum of the tasks' writtenBytes", true}},
            warnings);
  }
}

}  // namespace pagecache::formats::wfformat
