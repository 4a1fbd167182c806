// trace.json as Perfetto and chrome://tracing read it (the Trace Event Format): every event
// well formed, slices nested per track, async slices paired, counters numeric, timestamps in
// microseconds of simulated time; and its phase slices are timeline.csv's rows.
#include "support/csv.hpp"
#include "support/files.hpp"
#include "support/pcsim_cli.hpp"

#include <catch2/catch.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <tuple>
#include <vector>

namespace fs = std::filesystem;
using nlohmann::json;
using pagecache::testing::Outcome;
using pagecache::testing::pcsim;
using pagecache::testing::read_csv;
using pagecache::testing::scratch;
using pagecache::testing::slurp;

namespace {

json traced_run(const std::string& name, const std::string& args, fs::path& out) {
  out = scratch(name) / "out";
  const Outcome o = pcsim(fmt::format("run {} --trace --out '{}' --quiet", args, out.string()));
  INFO(o.output);
  REQUIRE(o.status == 0);
  REQUIRE(fs::exists(out / "trace.json"));
  return json::parse(slurp(out / "trace.json"));
}

// The Trace Event Format's rules, as far as pcsim uses it.
void check_format(const json& doc, double end_time_s) {
  REQUIRE(doc.is_object());
  REQUIRE(doc.at("traceEvents").is_array());
  const json& events = doc.at("traceEvents");
  REQUIRE(!events.empty());
  std::map<std::pair<int, int>, std::vector<std::pair<double, double>>> slices;  // per (pid, tid)
  std::map<std::tuple<std::string, std::string, std::uint64_t>, std::vector<std::pair<char, double>>> async;
  double latest = 0.0;
  for (const json& e : events) {
    INFO(e.dump());
    REQUIRE(e.contains("ph"));
    REQUIRE(e.contains("ts"));
    REQUIRE(e.contains("pid"));
    REQUIRE(e.contains("tid"));
    REQUIRE(e["ph"].is_string());
    REQUIRE(e["ts"].is_number());
    REQUIRE(e["pid"].is_number_integer());
    REQUIRE(e["tid"].is_number_integer());
    const std::string ph = e["ph"];
    const double ts = e["ts"];
    CHECK(ts >= 0.0);
    REQUIRE(std::string("XMCibe").find(ph) != std::string::npos);
    latest = std::max(latest, ts);
    if (ph == "X") {
      REQUIRE(e["dur"].is_number());
      CHECK(e["dur"].get<double>() >= 0.0);
      latest = std::max(latest, ts + e["dur"].get<double>());
      slices[{e["pid"], e["tid"]}].emplace_back(ts, ts + e["dur"].get<double>());
    } else if (ph == "C") {
      REQUIRE(e["args"].is_object());
      REQUIRE(!e["args"].empty());
      for (const auto& [key, value] : e["args"].items()) CHECK(value.is_number());
    } else if (ph == "i") {
      CHECK((e["s"] == "p" || e["s"] == "t" || e["s"] == "g"));
    } else if (ph == "b" || ph == "e") {
      REQUIRE(e["id"].is_number_integer());
      REQUIRE(e["cat"].is_string());
      async[{e["cat"], e["name"], e["id"]}].emplace_back(ph[0], ts);
    } else if (ph == "M") {
      REQUIRE(e["args"].contains(e["name"] == "process_sort_index" ? "sort_index" : "name"));
    }
  }
  // Slices on one track nest: each starts after the enclosing one starts and ends before it ends.
  for (auto& [track, spans] : slices) {
    std::sort(spans.begin(), spans.end(), [](const auto& a, const auto& b) { return a.first != b.first ? a.first < b.first : a.second > b.second; });
    std::vector<double> open;  // ends of the enclosing slices
    for (const auto& [b, e] : spans) {
      while (!open.empty() && open.back() <= b) open.pop_back();
      if (!open.empty()) CHECK(e <= open.back());
      open.push_back(e);
    }
  }
  // Every async slice begins once and ends once, not before it begins.
  for (const auto& [key, marks] : async) {
    REQUIRE(marks.size() == 2);
    const auto& begin = marks[0].first == 'b' ? marks[0] : marks[1];
    const auto& end = marks[0].first == 'b' ? marks[1] : marks[0];
    CHECK(begin.first == 'b');
    CHECK(end.first == 'e');
    CHECK(begin.second <= end.second);
  }
  // Microseconds of simulated time: the last event is at the run's end.
  CHECK(latest == Approx(end_time_s * 1e6).margin(1.0));  // summary.json has microseconds
}

double end_time(const fs::path& out) { return json::parse(slurp(out / "summary.json")).at("end_time_s"); }

}  // namespace

TEST_CASE("trace.json of Exp 2 with 8 pipelines keeps the format, and its phases are timeline.csv's rows", "[cli][trace]") {
  fs::path out;
  const json doc = traced_run("trace_exp2", fmt::format("'{}/scenarios/paper/exp2.toml' --set pipelines.count=8", PCSIM_SOURCE_DIR), out);
  check_format(doc, end_time(out));

  // The applications' tracks: tid -> name ("app", or "app #k" for a further lane).
  std::map<int, std::string> lane_app;
  for (const json& e : doc["traceEvents"]) {
    if (e["ph"] == "M" && e["name"] == "thread_name" && e["pid"] == 1) {
      std::string name = e["args"]["name"];
      if (const auto hash = name.rfind(" #"); hash != std::string::npos) name.resize(hash);
      lane_app[e["tid"]] = name;
    }
  }
  using Row = std::tuple<std::string, std::string, std::string, long long, long long>;  // app, task, phase, start and end in us
  const auto us = [](double v) { return std::llround(v); };
  std::multiset<Row> traced, timeline;
  for (const json& e : doc["traceEvents"]) {
    if (e["ph"] != "X" || e["cat"] != "phase") continue;
    const double ts = e["ts"], dur = e["dur"];
    // Named "TASK PHASE": the task, a space, the phase (the last word: a task's name may have spaces).
    const std::string name = e["name"], task = e["args"]["task"];
    const auto space = name.rfind(' ');
    REQUIRE(space != std::string::npos);
    CHECK(name.substr(0, space) == task);
    traced.insert({lane_app.at(e["tid"]), task, name.substr(space + 1), us(ts), us(ts + dur)});
  }
  for (const auto& r : read_csv((out / "timeline.csv").string())) {
    timeline.insert({r.at("app"), r.at("task"), r.at("phase"), us(std::stod(r.at("start_s")) * 1e6), us(std::stod(r.at("end_s")) * 1e6)});
  }
  CHECK(timeline.size() == 8 * 3 * 3);
  CHECK(traced == timeline);

  // A counter row per memory.csv row; device transfers and flushes are there.
  std::size_t counters = 0, flows = 0, flushes = 0;
  for (const json& e : doc["traceEvents"]) {
    counters += e["ph"] == "C";
    flows += e["ph"] == "b" && e["cat"] == "flow";
    flushes += e["ph"] == "i" && e["cat"] == "flush";
  }
  CHECK(counters == read_csv((out / "memory.csv").string()).size());
  CHECK(flows > 0);
  CHECK(flushes > 0);
  CHECK(doc["otherData"]["truncated"] == false);
}

TEST_CASE("trace.json of a workflow puts overlapping tasks on lanes of their workflow's track, slices named TASK PHASE", "[cli][trace]") {
  fs::path out;
  const json doc = traced_run("trace_workflow", fmt::format("'{}/golden/small_workflow.toml'", PCSIM_TEST_DIR), out);
  check_format(doc, end_time(out));
  // A slice per timeline.csv row, named after its task and phase.
  std::multiset<std::string> names, rows;
  for (const json& e : doc["traceEvents"])
    if (e["ph"] == "X") names.insert(e["name"].get<std::string>());
  for (const auto& r : read_csv((out / "timeline.csv").string())) rows.insert(r.at("task") + " " + r.at("phase"));
  CHECK(!rows.empty());
  CHECK(names == rows);
}

TEST_CASE("trace.json is written only when asked, by --trace or the scenario key", "[cli][trace]") {
  const fs::path dir = scratch("trace_off");
  const std::string scenario = fmt::format("'{}/golden/two_readers.toml'", PCSIM_TEST_DIR);
  REQUIRE(pcsim(fmt::format("run {} --out '{}' --quiet", scenario, (dir / "plain").string())).status == 0);
  CHECK_FALSE(fs::exists(dir / "plain" / "trace.json"));
  REQUIRE(pcsim(fmt::format("run {} --set trace=true --out '{}' --quiet", scenario, (dir / "key").string())).status == 0);
  CHECK(fs::exists(dir / "key" / "trace.json"));
  // The same inputs, the same trace.
  REQUIRE(pcsim(fmt::format("run {} --trace --out '{}' --quiet", scenario, (dir / "flag").string())).status == 0);
  CHECK(slurp(dir / "flag" / "trace.json") == slurp(dir / "key" / "trace.json"));
}
