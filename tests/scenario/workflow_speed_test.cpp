// compute = "speed" (src/scenario/workflow_speed.hpp): a recorded runtime times the recorded
// machine's speed (MHz x 10^6 flop/s, WRENCH's rule) over the speed of the host that runs the
// task; off by default, when the runtimes are taken as they are. The ratios below are worked
// out by hand.

#include "support/files.hpp"

#include <pagecache/error.hpp>
#include <pagecache/run.hpp>
#include <pagecache/scenario_file.hpp>

#include <catch2/catch.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

namespace pagecache {
namespace {

using nlohmann::json;

// Tasks a then b, 4 s and 6 s, recorded on machine "slow" of `mhz` MHz (no cpu speed if < 0).
json instance(double mhz) {
  json doc = json::parse(R"({
    "name": "sp", "schemaVersion": "1.5",
    "workflow": {
      "specification": {
        "tasks": [
          {"name": "A", "id": "a", "parents": [], "children": ["b"], "inputFiles": ["in"], "outputFiles": ["mid"]},
          {"name": "B", "id": "b", "parents": ["a"], "children": [], "inputFiles": ["mid"], "outputFiles": ["out"]}
        ],
        "files": [{"id": "in", "sizeInBytes": 1000000}, {"id": "mid", "sizeInBytes": 2000000}, {"id": "out", "sizeInBytes": 3000000}]
      },
      "execution": {
        "makespanInSeconds": 10, "executedAt": "2023-05-10T16:23:32Z",
        "tasks": [{"id": "a", "runtimeInSeconds": 4, "machines": ["slow"]}, {"id": "b", "runtimeInSeconds": 6, "machines": ["slow"]}],
        "machines": [{"nodeName": "slow", "cpu": {"coreCount": 8}}]
      }
    }
  })");
  if (mhz >= 0) doc["workflow"]["execution"]["machines"][0]["cpu"]["speedInMHz"] = mhz;
  return doc;
}

// A scenario of one host "fast" (its `speed` line as given, none if empty) running `doc`
// with the [workflow] table's `options`.
std::string scenario(const std::filesystem::path& dir, const json& doc, const std::string& speed, const std::string& options) {
  std::ofstream(dir / "w.json") << doc.dump();
  std::ofstream(dir / "s.toml") << fmt::format(R"([[hosts]]
name = "fast"
{}
cores = 8
memory = "16 GB"
memory_read_bw = "4 GB/s"
memory_write_bw = "4 GB/s"
[[hosts.disks]]
name = "d"
read_bw = "500 MB/s"
write_bw = "400 MB/s"

[workflow]
file = "w.json"
{}
)",
                                               speed, options);
  return (dir / "s.toml").string();
}

// Each task's compute phase in a run, in seconds.
std::map<std::string, double> compute_phases(const Scenario& s) {
  const RunResult r = run_scenario(s);
  std::map<std::string, double> out;
  for (const PhaseRow& row : r.timeline) {
    if (row.phase == PhaseKind::Compute) out[r.task_name(row)] = row.end - row.start;
  }
  return out;
}

std::string error_of(const std::string& file, const std::vector<std::pair<std::string, std::string>>& overrides = {}) {
  try {
    load_scenario(file, overrides);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(loaded)";
}

TEST_CASE("compute = \"speed\" scales each compute phase by the recorded machine's speed over the host's", "[scenario][workflow][speed]") {
  const std::filesystem::path dir = testing::scratch("workflow-speed");
  // Recorded at 1200 MHz = 1.2e9 flop/s, run on 2.4e9 flop/s: each phase takes half its runtime.
  const std::string file = scenario(dir, instance(1200), "speed = \"2.4Gf\"", "compute = \"speed\"");
  const Scenario s = load_scenario(file);
  REQUIRE(s.workflows.at(0).tasks.size() == 2);
  CHECK(s.workflows[0].tasks[0].compute == 2.0);
  CHECK(s.workflows[0].tasks[1].compute == 3.0);
  const std::map<std::string, double> phases = compute_phases(s);
  CHECK(phases.at("a") == Approx(2.0).epsilon(1e-12));
  CHECK(phases.at("b") == Approx(3.0).epsilon(1e-12));

  // Off (the default, or runtime): today's times, whatever the speeds.
  for (const std::string off : {"", "compute = \"runtime\""}) {
    INFO(off);
    const Scenario plain = load_scenario(scenario(dir, instance(1200), "speed = \"2.4Gf\"", off));
    CHECK(plain.workflows.at(0).tasks[0].compute == 4.0);
    CHECK(plain.workflows[0].tasks[1].compute == 6.0);
    const std::map<std::string, double> today = compute_phases(plain);
    CHECK(today.at("a") == Approx(4.0).epsilon(1e-12));
    CHECK(today.at("b") == Approx(6.0).epsilon(1e-12));
  }
  // From pcsim's --set, on a host of 0.8e9 flop/s (a number): 1.2e9 / 0.8e9, 1.5 times as long.
  const Scenario slower = load_scenario(scenario(dir, instance(1200), "speed = 0.8e9", ""), {{"workflow.compute", "speed"}});
  CHECK(slower.workflows.at(0).tasks[0].compute == 4.0 * 1.5);
  CHECK(slower.workflows[0].tasks[1].compute == 6.0 * 1.5);
}

TEST_CASE("compute = \"speed\" reads a SimGrid host's speed: 2400 MHz recorded, pegasus-5 of 1.2Gf, twice as long", "[scenario][workflow][speed]") {
  const std::filesystem::path dir = testing::scratch("workflow-speed-simgrid");
  json doc = instance(2400);
  doc["workflow"]["execution"]["machines"][0]["nodeName"] = "pegasus-5";
  for (json& r : doc["workflow"]["execution"]["tasks"]) r["machines"] = {"pegasus-5"};
  std::ofstream(dir / "w.json") << doc.dump();
  WorkflowOptions options;
  options.platform = (std::filesystem::path(PCSIM_SOURCE_DIR) / "platforms/wfcommons-chameleon.xml").string();
  const Scenario s = load_workflow((dir / "w.json").string(), options, {{"workflow.compute", "speed"}});
  REQUIRE(s.workflows.at(0).tasks.size() == 2);
  CHECK(s.workflows[0].tasks[0].host == "pegasus-5");
  CHECK(s.workflows[0].tasks[0].compute == 8.0);
  CHECK(s.workflows[0].tasks[1].compute == 12.0);
  const std::map<std::string, double> phases = compute_phases(s);
  CHECK(phases.at("a") == Approx(8.0).epsilon(1e-12));
  CHECK(phases.at("b") == Approx(12.0).epsilon(1e-12));
  CHECK(load_workflow((dir / "w.json").string(), options).workflows.at(0).tasks[0].compute == 4.0);
}

TEST_CASE("a machine without a speed takes reference_speed, WRENCH's reference flop rate", "[scenario][workflow][speed]") {
  const std::filesystem::path dir = testing::scratch("workflow-speed-reference");
  // 0.6e9 flop/s recorded, 2.4e9 on the host: a quarter of each runtime.
  const Scenario s = load_scenario(scenario(dir, instance(-1), "speed = \"2.4Gf\"", "compute = \"speed\"\nreference_speed = \"600Mf\""));
  CHECK(s.workflows.at(0).tasks[0].compute == 1.0);
  CHECK(s.workflows[0].tasks[1].compute == 1.5);
  // A machine's own speed wins over the reference.
  const Scenario own = load_scenario(scenario(dir, instance(1200), "speed = \"2.4Gf\"", "compute = \"speed\"\nreference_speed = \"600Mf\""));
  CHECK(own.workflows.at(0).tasks[0].compute == 2.0);
}

TEST_CASE("compute = \"speed\" refuses what it cannot scale, naming the file and key", "[scenario][workflow][speed]") {
  const std::filesystem::path dir = testing::scratch("workflow-speed-errors");
  const std::string w = (dir / "w.json").string();
  const std::string s = (dir / "s.toml").string();
  CHECK(error_of(scenario(dir, instance(1200), "", "compute = \"speed\"")) ==
        s + ":1:1: key 'hosts[0].speed': no speed, which compute = \"speed\" needs: give the host a speed in flop/s (\"1.2Gf\")");
  CHECK(error_of(scenario(dir, instance(0), "speed = \"2.4Gf\"", "compute = \"speed\"")) ==
        w + ": workflow.execution.machines[0] (machine 'slow'): cpu.speedInMHz: must be a number of MHz > 0 for compute = \"speed\", got 0");
  json text_speed = instance(1200);
  text_speed["workflow"]["execution"]["machines"][0]["cpu"]["speedInMHz"] = "fast";
  CHECK(error_of(scenario(dir, text_speed, "speed = \"2.4Gf\"", "compute = \"speed\"")) ==
        w + ": workflow.execution.machines[0] (machine 'slow'): cpu.speedInMHz: must be a number of MHz > 0 for compute = \"speed\", got no "
            "number");
  CHECK(error_of(scenario(dir, instance(-1), "speed = \"2.4Gf\"", "compute = \"speed\"")) ==
        w + ": task 'a': machines: the instance gives its machine no cpu speed, so compute = \"speed\" has no speed to scale from: give "
            "reference_speed (the flop/s of the machine its runtime was measured on)");
  json unlisted = instance(1200);
  unlisted["workflow"]["execution"].erase("machines");
  CHECK(error_of(scenario(dir, unlisted, "speed = \"2.4Gf\"", "compute = \"speed\"")) ==
        w + ": task 'a': machines: 'slow' is no machine of the instance's list, so its speed is unknown (compute = \"speed\")");
  json two = instance(1200);
  two["workflow"]["execution"]["machines"].push_back({{"nodeName", "other"}, {"cpu", {{"speedInMHz", 2400}}}});
  two["workflow"]["execution"]["tasks"][1]["machines"] = {"slow", "other"};
  CHECK(error_of(scenario(dir, two, "speed = \"2.4Gf\"", "compute = \"speed\"")) ==
        w + ": task 'b': machines: ran on 'slow' (1200 MHz) and 'other' (2400 MHz): compute = \"speed\" needs one speed per task");
  CHECK(error_of(scenario(dir, instance(1200), "speed = 0", "compute = \"speed\"")) == s + ":3:9: key 'hosts[0].speed': must be > 0 flop/s, got 0");
  CHECK(error_of(scenario(dir, instance(1200), "speed = \"2.4 GHz\"", "")).rfind(s + ":3:9: key 'hosts[0].speed': ", 0) == 0);
  CHECK(error_of(scenario(dir, instance(1200), "speed = \"2.4Gf\"", "reference_speed = \"1Gf\"")) ==
        s + ":15:19: key 'workflow.reference_speed': is read by compute = \"speed\" alone");
  CHECK(error_of(scenario(dir, instance(1200), "speed = \"2.4Gf\"", "compute = \"flops\"")) ==
        s + ":15:11: key 'workflow.compute': unknown 'flops' (use \"runtime\", \"cpu_share\" or \"speed\")");
  // Without compute = "speed", none of it matters: a machine's speed of 0, a host without one.
  CHECK(error_of(scenario(dir, instance(0), "", "")) == "(loaded)");
}

TEST_CASE("compute = \"speed\" with unplaced tasks needs the workflow's hosts to share one speed", "[scenario][workflow][speed]") {
  const std::filesystem::path dir = testing::scratch("workflow-speed-hosts");
  std::ofstream(dir / "w.json") << instance(1200).dump();
  const std::string host = R"([[hosts]]
name = "{}"
speed = "{}"
memory = "16 GB"
memory_read_bw = "4 GB/s"
memory_write_bw = "4 GB/s"
[[hosts.disks]]
name = "d"
read_bw = "500 MB/s"
write_bw = "400 MB/s"
)";
  const auto write = [&](const std::string& second_speed) {
    std::ofstream(dir / "s.toml") << fmt::format(fmt::runtime(host), "h1", "1.2Gf") << fmt::format(fmt::runtime(host), "h2", second_speed)
                                  << "[[links]]\nname = \"l\"\nbandwidth = \"1 GB/s\"\nlatency = \"1 us\"\nhosts = [\"h1\", \"h2\"]\n"
                                  << "[workflow]\nfile = \"w.json\"\ncompute = \"speed\"\nhosts = [\"h1\", \"h2\"]\n";
    return (dir / "s.toml").string();
  };
  CHECK(load_scenario(write("1.2Gf")).workflows.at(0).tasks[0].compute == 4.0);
  CHECK(error_of(write("2.4Gf")) == (dir / "s.toml").string() +
                                        ":29:9: key 'workflow.hosts': hosts 'h1' (1200000000 flop/s) and 'h2' (2400000000 flop/s) differ in "
                                        "speed, and compute = \"speed\" scales a runtime before the run chooses its host: give hosts of one "
                                        "speed, or record each task's machine among them");
}

}  // namespace
}  // namespace pagecache
