#pragma once
// The workflow reader's contract, as fuzz/workflow_fuzzer.cpp checks it on every input and
// tests/scenario/workflow_json_test.cpp on the reference workflows, the seeds and hostile inputs:
// any bytes either read as a workflow or are refused with ConfigError; any other exception, a
// crash, a hang, unbounded memory or a sanitizer report is a bug. A workflow that reads keeps
// its promises, checked here without the reader's code: indices in range and without repeats,
// ids unique, parents acyclic (Kahn's algorithm, not the reader's depth-first search), every
// number in its range.

#include "formats/wfformat/workflow_json.hpp"

#include <pagecache/error.hpp>
#include <pagecache/units.hpp>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <set>
#include <string>
#include <vector>

namespace pagecache::fuzz {

/// The limits inputs are read with (as pcsim would read a workflow: 10^4 tasks take well under
/// a second under the sanitizers).
inline constexpr std::int64_t kFuzzMaxTasks = 10'000;
inline constexpr std::int64_t kFuzzMaxFiles = 100'000;

/// "" if every index of `list` is below `size` and none repeats, else what is wrong.
inline std::string index_problem(const std::vector<std::size_t>& list, std::size_t size, const char* what) {
  std::set<std::size_t> seen;
  for (std::size_t i : list) {
    if (i >= size) return std::string(what) + " index " + std::to_string(i) + " out of range";
    if (!seen.insert(i).second) return std::string(what) + " index " + std::to_string(i) + " repeated";
  }
  return {};
}

/// "" if `w` keeps the reader's promises, else the first one broken.
inline std::string workflow_problem(const formats::wfformat::WfWorkflow& w) {
  if (w.format != "WfFormat 1.5" && w.format != "WfFormat 1.6" && w.format != "WRENCH 2.x (schema before 1.5)") {
    return "unknown format '" + w.format + "'";
  }
  if (w.tasks.empty()) return "no tasks";
  if (w.tasks.size() > static_cast<std::size_t>(kFuzzMaxTasks)) return "more tasks than the limit";
  if (w.files.size() > static_cast<std::size_t>(kFuzzMaxFiles)) return "more files than the limit";
  if (w.warnings.size() > formats::wfformat::kMaxWorkflowWarnings) return "more warnings than the limit";
  if (!(w.makespan == -1 || (w.makespan >= 0 && w.makespan <= units::kMaxSeconds))) return "makespan out of range";
  std::set<std::string> ids;
  for (const formats::wfformat::WfFile& f : w.files) {
    if (f.id.empty() || !ids.insert(f.id).second) return "file id empty or repeated: " + f.id;
    if (f.size < 0 || f.size > units::kMaxBytes) return "file size out of range: " + f.id;
  }
  const std::set<std::string> machines(w.machines.begin(), w.machines.end());
  if (machines.size() != w.machines.size()) return "a machine listed twice";
  if (w.machine_speeds.size() != w.machines.size()) return "not one speed per machine";
  for (const formats::wfformat::WfMachineSpeed& speed : w.machine_speeds) {
    if (speed.place.empty()) return "a machine's speed without its place";
  }
  ids.clear();
  for (std::size_t t = 0; t < w.tasks.size(); ++t) {
    const formats::wfformat::WfTask& task = w.tasks[t];
    if (task.id.empty() || !ids.insert(task.id).second) return "task id empty or repeated: " + task.id;
    if (!std::isfinite(task.runtime) || task.runtime < 0 || task.runtime > units::kMaxSeconds) return "runtime out of range: " + task.id;
    if (task.cores < 1 || task.cores > 1'000'000) return "cores out of range: " + task.id;
    if (task.memory < 0 || task.memory > units::kMaxBytes) return "memory out of range: " + task.id;
    if (!(task.avg_cpu == -1 || (task.avg_cpu >= 0 && task.avg_cpu <= 1e8))) return "avg_cpu out of range: " + task.id;
    for (const std::string& m : task.machines) {
      if (m.empty() || (!machines.empty() && machines.count(m) == 0)) return "unknown machine in task " + task.id;
    }
    for (const std::string& problem : {index_problem(task.parents, w.tasks.size(), "parent"), index_problem(task.inputs, w.files.size(), "input"),
                                       index_problem(task.outputs, w.files.size(), "output")}) {
      if (!problem.empty()) return problem + " in task " + task.id;
    }
  }
  // Kahn's algorithm: a task is ready once all its parents are done; a cycle leaves some never ready.
  std::vector<std::size_t> waiting(w.tasks.size());
  std::vector<std::vector<std::size_t>> children(w.tasks.size());
  std::vector<std::size_t> ready;
  for (std::size_t t = 0; t < w.tasks.size(); ++t) {
    waiting[t] = w.tasks[t].parents.size();
    for (std::size_t p : w.tasks[t].parents) children[p].push_back(t);
    if (waiting[t] == 0) ready.push_back(t);
  }
  std::size_t done = 0;
  while (!ready.empty()) {
    const std::size_t t = ready.back();
    ready.pop_back();
    ++done;
    for (std::size_t c : children[t]) {
      if (--waiting[c] == 0) ready.push_back(c);
    }
  }
  if (done != w.tasks.size()) return "the parents form a cycle";
  return {};
}

/// "" if `text` keeps the contract, else what broke. Exceptions other than ConfigError are
/// not caught: in the fuzzer they end the process where they were thrown, in a test Catch2
/// reports them.
inline std::string check_workflow_text(const std::string& text, const std::string& source_name) {
  formats::wfformat::WfWorkflow w;
  try {
    w = formats::wfformat::read_workflow_json(text, source_name, kFuzzMaxTasks, kFuzzMaxFiles);
  } catch (const ConfigError& e) {
    if (std::string(e.what()).rfind(source_name, 0) != 0) return std::string("an error that does not name the file: ") + e.what();
    return {};
  }
  return workflow_problem(w);
}

}  // namespace pagecache::fuzz
