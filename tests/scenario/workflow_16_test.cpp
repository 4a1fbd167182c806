// WfFormat 1.6 (wfcommons/WfFormat, README "What's New in 1.6"): a 1.5 instance with the
// version changed and optional figures about the workflow (metrics), which the reader checks
// against the workflow: a disagreement is a warning naming both numbers, a malformed figure an
// error naming the file, path and key. 1.5 files read as before, metrics or not.

#include "formats/wfformat/workflow_json.hpp"

#include "support/files.hpp"

#include <pagecache/error.hpp>
#include <pagecache/run.hpp>
#include <pagecache/scenario_file.hpp>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace pagecache::scenario {
using namespace pagecache::formats;
using namespace pagecache::formats::wfformat;
namespace {

using nlohmann::json;

const std::filesystem::path kInstances = std::filesystem::path(PAGECACHE_INPUTS_DIR) / "wfcommons" / "instances";

json instance(const char* name) { return json::parse(testing::slurp(kInstances / name)); }

WfWorkflow read(const json& doc) { return read_workflow_json(doc.dump(), "w.json", 100'000, 100'000); }

std::string error_of(const json& doc) {
  try {
    read(doc);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(read without an error)";
}

// The two-task workflow of workflow_json_test.cpp as 1.6, figures right: a then b, 600 bytes
// of files, 10.25 s of runtimes, 7 bytes read and 9 written.
json small_16() {
  return json::parse(R"({
    "name": "small", "schemaVersion": "1.6",
    "workflow": {
      "specification": {
        "tasks": [
          {"name": "A", "id": "a", "parents": [], "children": ["b"], "inputFiles": ["in"], "outputFiles": ["mid"]},
          {"name": "B", "id": "b", "parents": ["a"], "children": [], "inputFiles": ["mid", "in"], "outputFiles": ["out"]}
        ],
        "files": [{"id": "in", "sizeInBytes": 100}, {"id": "mid", "sizeInBytes": 200}, {"id": "out", "sizeInBytes": 300}],
        "metrics": {"numberOfTasks": 2, "numberOfFiles": 3, "sumOfFileSizesInBytes": 600, "numberOfLevels": 2,
                    "minimumWidth": 1, "maximumWidth": 1}
      },
      "execution": {
        "makespanInSeconds": 10.5, "executedAt": "2023-05-10T16:23:32Z",
        "tasks": [
          {"id": "a", "runtimeInSeconds": 4.25, "readBytes": 3, "writtenBytes": 9},
          {"id": "b", "runtimeInSeconds": 6, "readBytes": 4}
        ],
        "metrics": {"sumTaskRuntimesInSeconds": 10.25, "totalNumBytesRead": 7, "totalNumBytesWritten": 9}
      }
    }
  })");
}

// The figures of WfFormat's tools/wfcommons-add-metrics-to-instance.py, computed here another
// way: a task's level is one below its deepest parent's, found by recursion (the tool walks
// the graph level by level). Execution sums only when positive, as the tool writes them.
void add_metrics(json& doc) {
  json& spec = doc["workflow"]["specification"];
  json& execution = doc["workflow"]["execution"];
  std::map<std::string, const json*> by_id;
  for (const json& t : spec["tasks"]) by_id[t["id"].get<std::string>()] = &t;
  std::map<std::string, int> level;
  const std::function<int(const std::string&)> level_of = [&](const std::string& id) {
    if (const auto it = level.find(id); it != level.end()) return it->second;
    int deepest = -1;
    for (const json& p : (*by_id.at(id))["parents"]) deepest = std::max(deepest, level_of(p.get<std::string>()));
    return level[id] = deepest + 1;
  };
  std::map<int, std::int64_t> width;
  for (const auto& [id, task] : by_id) ++width[level_of(id)];
  std::int64_t bytes = 0;
  for (const json& f : spec["files"]) bytes += f["sizeInBytes"].get<std::int64_t>();
  std::int64_t narrowest = width.begin()->second, widest = 0;
  for (const auto& [l, w] : width) narrowest = std::min(narrowest, w), widest = std::max(widest, w);
  spec["metrics"] = {{"numberOfTasks", spec["tasks"].size()}, {"numberOfFiles", spec["files"].size()}, {"sumOfFileSizesInBytes", bytes},
                     {"numberOfLevels", width.size()}, {"minimumWidth", narrowest}, {"maximumWidth", widest}};
  double runtimes = 0;
  std::int64_t read_bytes = 0, written = 0;
  for (const json& r : execution["tasks"]) {
    runtimes += r["runtimeInSeconds"].get<double>();
    read_bytes += r.value("readBytes", std::int64_t{0});
    written += r.value("writtenBytes", std::int64_t{0});
  }
  json& m = execution["metrics"] = json::object();
  if (runtimes > 0) m["sumTaskRuntimesInSeconds"] = runtimes;
  if (read_bytes > 0) m["totalNumBytesRead"] = read_bytes;
  if (written > 0) m["totalNumBytesWritten"] = written;
  doc["schemaVersion"] = "1.6";
}

void check_same_workflow(const WfWorkflow& a, const WfWorkflow& b) {
  CHECK(a.makespan == b.makespan);
  CHECK(a.machines == b.machines);
  REQUIRE(a.files.size() == b.files.size());
  for (std::size_t i = 0; i < a.files.size(); ++i) CHECK((a.files[i].id == b.files[i].id && a.files[i].size == b.files[i].size));
  REQUIRE(a.tasks.size() == b.tasks.size());
  for (std::size_t i = 0; i < a.tasks.size(); ++i) {
    const WfTask& x = a.tasks[i];
    const WfTask& y = b.tasks[i];
    CHECK((x.id == y.id && x.runtime == y.runtime && x.cores == y.cores && x.parents == y.parents && x.inputs == y.inputs &&
           x.outputs == y.outputs && x.machines == y.machines));
  }
}

TEST_CASE("bacass rewritten as WfFormat 1.6 writes it reads as its 1.5 self, every figure agreeing", "[scenario][workflow][wfformat16]") {
  const json v15 = instance("bacass-dirt02-001.json");
  json v16 = v15;
  v16["schemaVersion"] = "1.6";
  // Worked out from the file as the tool computes them: 11 tasks; 67 files of 525544057 bytes;
  // five levels, of 1 to 4 tasks; 3961.87 s of runtimes; 10657024995 bytes read, 30358190013 written.
  v16["workflow"]["specification"]["metrics"] = {{"numberOfTasks", 11}, {"numberOfFiles", 67}, {"sumOfFileSizesInBytes", 525544057},
                                                 {"numberOfLevels", 5}, {"minimumWidth", 1}, {"maximumWidth", 4}};
  v16["workflow"]["execution"]["metrics"] = {
      {"sumTaskRuntimesInSeconds", 3961.87}, {"totalNumBytesRead", 10657024995}, {"totalNumBytesWritten", 30358190013}};
  const WfWorkflow w16 = read(v16);
  CHECK(w16.format == "WfFormat 1.6");
  CHECK(w16.warnings.empty());
  const WfWorkflow w15 = read(v15);
  CHECK(w15.format == "WfFormat 1.5");
  check_same_workflow(w15, w16);
}

TEST_CASE("every WfCommons instance with its 1.6 figures added reads without a warning", "[scenario][workflow][wfformat16]") {
  for (const auto& entry : std::filesystem::directory_iterator(kInstances)) {
    INFO(entry.path().filename().string());
    json doc = json::parse(testing::slurp(entry.path()));
    const WfWorkflow w15 = read(doc);
    add_metrics(doc);
    const WfWorkflow w16 = read(doc);
    CHECK(w16.warnings == std::vector<std::string>{});
    check_same_workflow(w15, w16);
  }
}

TEST_CASE("a WfFormat 1.6 figure that disagrees with the workflow is a warning naming both numbers", "[scenario][workflow][wfformat16]") {
  CHECK(read(small_16()).warnings.empty());
  json doc = small_16();
  json& spec = doc["workflow"]["specification"]["metrics"];
  json& execution = doc["workflow"]["execution"]["metrics"];
  spec["numberOfTasks"] = 3;
  spec["numberOfLevels"] = 1;
  spec["maximumWidth"] = 2;
  execution["sumTaskRuntimesInSeconds"] = 10.5;
  execution["totalNumBytesWritten"] = 0;
  const std::string s = "w.json: workflow.specification.metrics: ";
  const std::string e = "w.json: workflow.execution.metrics: ";
  CHECK(read(doc).warnings ==
        std::vector<std::string>{
            s + "numberOfTasks: declares 3, but the workflow gives 2 (tasks in workflow.specification.tasks); the figure is ignored",
            s + "numberOfLevels: declares 1, but the workflow gives 2 (levels of the task graph); the figure is ignored",
            s + "maximumWidth: declares 2, but the workflow gives 1 (tasks in the widest level); the figure is ignored",
            e + "sumTaskRuntimesInSeconds: declares 10.5, but the workflow gives 10.25 (the sum of the tasks' runtimeInSeconds); the figure is "
                "ignored",
            e + "totalNumBytesWritten: declares 0, but the workflow gives 9 (the sum of the tasks' writtenBytes); the figure is ignored"});
  // Within WfFormat's validator's relative tolerance (1e-9), a sum agrees.
  doc = small_16();
  doc["workflow"]["execution"]["metrics"]["sumTaskRuntimesInSeconds"] = 10.25 * (1 + 1e-12);
  CHECK(read(doc).warnings.empty());
}

TEST_CASE("each broken WfFormat 1.6 figure is refused naming the file, the path and the key", "[scenario][workflow][wfformat16]") {
  struct Case {
    json::json_pointer at;
    json value;
    std::string message;
  };
  const std::string s = "w.json: workflow.specification.metrics: ";
  const std::string e = "w.json: workflow.execution.metrics: ";
  const std::vector<Case> cases = {
      {"/workflow/specification/metrics"_json_pointer, json::array(), "w.json: workflow.specification: metrics: expected an object, got an array"},
      {"/workflow/execution/metrics"_json_pointer, 5, "w.json: workflow.execution: metrics: expected an object, got a number"},
      {"/workflow/specification/metrics/numberOfTasks"_json_pointer, "2", s + "numberOfTasks: expected a whole number, got a string"},
      {"/workflow/specification/metrics/numberOfFiles"_json_pointer, -3, s + "numberOfFiles: must not be negative, got -3"},
      {"/workflow/specification/metrics/sumOfFileSizesInBytes"_json_pointer, 600.5, s + "sumOfFileSizesInBytes: must be a whole number, got 600.5"},
      {"/workflow/specification/metrics/minimumWidth"_json_pointer, nullptr, s + "minimumWidth: expected a whole number, got null"},
      {"/workflow/execution/metrics/sumTaskRuntimesInSeconds"_json_pointer, "10", e + "sumTaskRuntimesInSeconds: expected a number, got a string"},
      {"/workflow/execution/metrics/sumTaskRuntimesInSeconds"_json_pointer, -1, e + "sumTaskRuntimesInSeconds: must not be negative, got -1"},
      {"/workflow/execution/metrics/totalNumBytesRead"_json_pointer, 7.5, e + "totalNumBytesRead: must be a whole number, got 7.5"},
  };
  for (const Case& c : cases) {
    INFO(c.at.to_string());
    json doc = small_16();
    doc[c.at] = c.value;
    CHECK(error_of(doc) == c.message);
  }
}

TEST_CASE("a WfFormat 1.5 file reads as before: metrics in it are not read", "[scenario][workflow][wfformat16]") {
  json doc = small_16();
  doc["schemaVersion"] = "1.5";
  doc["workflow"]["specification"]["metrics"] = {{"numberOfTasks", "many"}, {"numberOfLevels", 99}};
  const WfWorkflow w = read(doc);
  CHECK(w.format == "WfFormat 1.5");
  CHECK(w.warnings.empty());
}

TEST_CASE("1000Genome as WfFormat 1.6 runs as its 1.5 self on the Chameleon platform", "[scenario][workflow][wfformat16]") {
  const std::filesystem::path dir = testing::scratch("wfformat16-run");
  const std::string v15 = (kInstances / "1000genome-chameleon-2ch-100k-001.json").string();
  json doc = instance("1000genome-chameleon-2ch-100k-001.json");
  add_metrics(doc);
  // As worked out from the file: 52 tasks, 64 files, three levels of 2 to 28 tasks, no bytes read.
  CHECK(doc["workflow"]["specification"]["metrics"] == json({{"numberOfTasks", 52}, {"numberOfFiles", 64}, {"sumOfFileSizesInBytes", 2584828544},
                                                             {"numberOfLevels", 3}, {"minimumWidth", 2}, {"maximumWidth", 28}}));
  const std::string v16 = (dir / "1000genome-16.json").string();
  std::ofstream(v16) << doc.dump(4);
  WorkflowOptions options;
  options.platform = (std::filesystem::path(PCSIM_SOURCE_DIR) / "platforms/wfcommons-chameleon.xml").string();
  const Scenario s16 = load_workflow(v16, options);
  const RunResult r15 = run_scenario(load_workflow(v15, options));
  const RunResult r16 = run_scenario(s16);
  CHECK(r16.summary.makespan > 0);
  CHECK(r16.summary.makespan == r15.summary.makespan);
  CHECK(r16.summary.compute.seconds == r15.summary.compute.seconds);
  CHECK(r16.timeline.size() == r15.timeline.size());
}

}  // namespace
}  // namespace pagecache::scenario
