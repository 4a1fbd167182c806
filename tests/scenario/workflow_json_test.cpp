// The workflow reader (src/formats/wfformat/workflow_json.hpp) on the real inputs (WfCommons' WfFormat
// 1.5 instances, the WRENCH page-cache workflows) checked against the JSON read independently,
// and on broken and hostile inputs checked for the message: the file, the JSON path, the key,
// or the line and column.

#include "formats/common/json_text.hpp"
#include "formats/wfformat/workflow_json.hpp"

#include "support/files.hpp"

#include "workflow_property.hpp"

#include <pagecache/error.hpp>
#include <pagecache/scenario_file.hpp>

#include <catch2/catch.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

namespace pagecache::scenario {
using namespace pagecache::formats;
using namespace pagecache::formats::wfformat;
namespace {

using nlohmann::json;

const std::filesystem::path kInputs = PAGECACHE_INPUTS_DIR;

WfWorkflow read(const std::string& text, std::int64_t max_tasks = 100'000, std::int64_t max_files = 100'000) {
  return read_workflow_json(text, "w.json", max_tasks, max_files);
}

// The ConfigError's message, or a text no test expects.
std::string error_of(const std::string& text, std::int64_t max_tasks = 100'000, std::int64_t max_files = 100'000) {
  try {
    read(text, max_tasks, max_files);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(read without an error)";
}

std::string error_of_doc(const json& doc) { return error_of(doc.dump()); }

// Two tasks, a then b, on three files, with their execution records: every field set once.
json small_wfformat() {
  return json::parse(R"({
    "name": "small", "schemaVersion": "1.5",
    "workflow": {
      "specification": {
        "tasks": [
          {"name": "A", "id": "a", "parents": [], "children": ["b"], "inputFiles": ["in"], "outputFiles": ["mid"]},
          {"name": "B", "id": "b", "parents": ["a"], "children": [], "inputFiles": ["mid", "in"], "outputFiles": ["out"]}
        ],
        "files": [{"id": "in", "sizeInBytes": 100}, {"id": "mid", "sizeInBytes": 200}, {"id": "out", "sizeInBytes": 300}]
      },
      "execution": {
        "makespanInSeconds": 10.5, "executedAt": "2023-05-10T16:23:32Z",
        "tasks": [
          {"id": "a", "runtimeInSeconds": 4.25, "coreCount": 2, "memoryInBytes": 1000, "avgCPU": 150.5, "machines": ["m1"]},
          {"id": "b", "runtimeInSeconds": 6}
        ],
        "machines": [{"nodeName": "m1"}, {"nodeName": "m2"}]
      }
    }
  })");
}

// The same two tasks in the format before 1.5, as the WRENCH page-cache inputs write it.
json small_old_format() {
  return json::parse(R"({
    "name": "small-old",
    "workflow": {
      "tasks": [
        {"name": "t1", "type": "compute", "runtime": 1.5, "cores": 2, "memory": 1000, "parents": [], "childrens": ["t2"],
         "files": [{"link": "input", "name": "f1", "size": 10}, {"link": "output", "name": "f2", "size": 20}]},
        {"name": "t2", "type": "compute", "runtime": 2, "parents": ["t1"], "childrens": [],
         "files": [{"link": "input", "name": "f2", "size": 20}, {"link": "output", "name": "f3", "size": 30}]}
      ]
    }
  })");
}

std::vector<std::string> ids_of(const std::vector<std::size_t>& indices, const std::vector<WfTask>& tasks) {
  std::vector<std::string> out;
  for (std::size_t i : indices) out.push_back(tasks.at(i).id);
  return out;
}

std::vector<std::string> ids_of(const std::vector<std::size_t>& indices, const std::vector<WfFile>& files) {
  std::vector<std::string> out;
  for (std::size_t i : indices) out.push_back(files.at(i).id);
  return out;
}

// Removes the key or array item `at` names.
void remove(json& doc, const json::json_pointer& at) {
  json& parent = doc[at.parent_pointer()];
  if (parent.is_array()) parent.erase(std::stoul(at.back()));
  else parent.erase(at.back());
}

std::vector<std::string> strings_of(const json& array) { return array.get<std::vector<std::string>>(); }

std::int64_t total_bytes(const WfWorkflow& w) {
  std::int64_t sum = 0;
  for (const WfFile& f : w.files) sum += f.size;
  return sum;
}

TEST_CASE("every WfCommons instance reads as its JSON says: counts, sizes, dependencies and each task's record", "[scenario][workflow]") {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(kInputs / "wfcommons" / "instances")) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  REQUIRE(files.size() == 8);
  for (const auto& path : files) {
    INFO(path.filename().string());
    const std::string text = testing::slurp(path);
    const WfWorkflow w = read_workflow_json(text, path.string(), 100'000, 100'000);
    // The same JSON walked directly, as the schema describes it.
    const json doc = json::parse(text);
    const json& spec = doc["workflow"]["specification"];
    const json& execution = doc["workflow"]["execution"];
    CHECK(w.file == path.string());
    CHECK(w.format == "WfFormat 1.5");
    CHECK(w.name == doc["name"].get<std::string>());
    CHECK(w.makespan == execution["makespanInSeconds"].get<double>());
    CHECK(w.warnings.empty());
    REQUIRE(w.files.size() == spec["files"].size());
    std::int64_t bytes = 0;
    for (std::size_t i = 0; i < w.files.size(); ++i) {
      CHECK(w.files[i].id == spec["files"][i]["id"].get<std::string>());
      CHECK(w.files[i].size == spec["files"][i]["sizeInBytes"].get<std::int64_t>());
      bytes += spec["files"][i]["sizeInBytes"].get<std::int64_t>();
    }
    CHECK(total_bytes(w) == bytes);
    std::vector<std::string> machines;
    for (const json& m : execution["machines"]) machines.push_back(m["nodeName"].get<std::string>());
    CHECK(w.machines == machines);
    std::map<std::string, const json*> record;
    for (const json& r : execution["tasks"]) record[r["id"].get<std::string>()] = &r;
    REQUIRE(w.tasks.size() == spec["tasks"].size());
    for (std::size_t i = 0; i < w.tasks.size(); ++i) {
      const WfTask& t = w.tasks[i];
      const json& s = spec["tasks"][i];
      INFO(t.id);
      CHECK(t.id == s["id"].get<std::string>());
      CHECK(t.name == s["name"].get<std::string>());
      CHECK(ids_of(t.parents, w.tasks) == strings_of(s["parents"]));
      CHECK(ids_of(t.inputs, w.files) == strings_of(s["inputFiles"]));
      CHECK(ids_of(t.outputs, w.files) == strings_of(s["outputFiles"]));
      const json& r = *record.at(t.id);
      CHECK(t.runtime == r["runtimeInSeconds"].get<double>());
      CHECK(t.cores == r.value("coreCount", 1));
      CHECK(t.memory == r.value("memoryInBytes", std::int64_t{0}));
      CHECK(t.avg_cpu == r.value("avgCPU", -1.0));
      CHECK(t.machines == r.value("machines", std::vector<std::string>{}));
    }
  }
}

TEST_CASE("the WfCommons instances' figures, checked by hand against the files", "[scenario][workflow]") {
  const auto load = [](const char* name) {
    const std::filesystem::path path = kInputs / "wfcommons" / "instances" / name;
    return read_workflow_json(testing::slurp(path), path.string(), 100'000, 100'000);
  };
  const WfWorkflow montage = load("montage-chameleon-dss-05d-001.json");
  CHECK(montage.tasks.size() == 58);
  CHECK(montage.files.size() == 111);
  CHECK(total_bytes(montage) == 2'795'142'706);
  CHECK(montage.makespan == 870.0);

  // blast: two machines, and a task with its cores, memory and machine recorded.
  const WfWorkflow blast = load("blast-chameleon-small-001.json");
  CHECK(blast.tasks.size() == 43);
  CHECK(blast.files.size() == 127);
  CHECK(total_bytes(blast) == 5'112'434'776);
  CHECK(blast.machines == std::vector<std::string>{"worker-1.novalocal", "worker-2.novalocal"});
  const WfTask& blastall = blast.tasks[1];
  CHECK(blastall.id == "blastall_ID000002");
  CHECK(blastall.runtime == 9.798843);
  CHECK(blastall.cores == 1);
  CHECK(blastall.memory == 484'000'000);
  CHECK(blastall.avg_cpu == 99.9326);
  CHECK(blastall.machines == std::vector<std::string>{"worker-2.novalocal"});
  CHECK(blastall.parents == std::vector<std::size_t>{0});
  CHECK(ids_of(blastall.inputs, blast.files) == std::vector<std::string>{"blastall", "small.fasta.0", "nt"});
  CHECK(blast.files[blastall.inputs[2]].size == 5'112'425'635);
  CHECK(ids_of(blastall.outputs, blast.files) == std::vector<std::string>{"small.fasta.0.out", "small.fasta.0.err"});
  CHECK(blast.tasks[42].parents.size() == 40);

  // bacass: ids differ from names; no machine per task, no cores (so 1).
  const WfWorkflow bacass = load("bacass-dirt02-001.json");
  CHECK(bacass.tasks[0].id == "NFCORE_BACASS.BACASS.FASTQC_2");
  CHECK(bacass.tasks[0].name == "NFCORE_BACASS.BACASS.FASTQC");
  CHECK(bacass.tasks[0].runtime == 37.0);
  CHECK(bacass.tasks[0].memory == 356'302'848);
  CHECK(bacass.tasks[0].cores == 1);
  CHECK(bacass.tasks[0].machines.empty());
  CHECK(bacass.machines == std::vector<std::string>{"dirt02"});
  CHECK(bacass.makespan == 4243.0);

  const WfWorkflow chain = load("helloworld-chain-5-chameleon.json");
  CHECK(chain.tasks.size() == 5);
  CHECK(total_bytes(chain) == 6 * 16'666'667);
  CHECK(chain.tasks[1].parents == std::vector<std::size_t>{0});
  CHECK(chain.tasks[1].runtime == 100.12);
  CHECK(chain.tasks[1].memory == 88'688);
  CHECK(chain.tasks[1].avg_cpu == 59.9441);
}

TEST_CASE("the WRENCH page-cache workflows read in the format before 1.5", "[scenario][workflow]") {
  const std::filesystem::path dir = kInputs / "wrench-cache";
  const WfWorkflow simple = read_workflow_json(testing::slurp(dir / "simple_workflow.json"), "simple_workflow.json", 100, 100);
  CHECK(simple.format == "WRENCH 2.x (schema before 1.5)");
  CHECK(simple.name == "simple-workflow");
  CHECK(simple.makespan == -1);
  CHECK(simple.warnings.empty());
  REQUIRE(simple.tasks.size() == 3);
  REQUIRE(simple.files.size() == 4);
  CHECK(total_bytes(simple) == 4 * 75'000'000'000);
  const WfTask& task02 = simple.tasks[1];
  CHECK(task02.id == "task02");
  CHECK(task02.runtime == 0.110);
  CHECK(task02.cores == 1);
  CHECK(task02.memory == 75'000'000'000);
  CHECK(task02.avg_cpu == -1);
  CHECK(task02.parents == std::vector<std::size_t>{0});
  CHECK(ids_of(task02.inputs, simple.files) == std::vector<std::string>{"file2.dat"});
  CHECK(ids_of(task02.outputs, simple.files) == std::vector<std::string>{"file3.dat"});

  const WfWorkflow nighres = read_workflow_json(testing::slurp(dir / "nighres_workflow.json"), "nighres_workflow.json", 100, 100);
  REQUIRE(nighres.tasks.size() == 4);
  CHECK(nighres.files.size() == 32);  // distinct names, in first-seen order
  CHECK(nighres.files.front().id == "sub001_sess1_INV2.nii");
  CHECK(nighres.files.back().id == "sub001_sess1_left_cerebrum_cruise-pcsf.nii");
  CHECK(total_bytes(nighres) == 9'043'979'264);  // with the first size of each file
  const std::vector<std::size_t> inputs = {3, 2, 4, 4};
  const std::vector<std::size_t> outputs = {4, 4, 9, 8};
  for (std::size_t i = 0; i < 4; ++i) {
    CHECK(nighres.tasks[i].inputs.size() == inputs[i]);
    CHECK(nighres.tasks[i].outputs.size() == outputs[i]);
    CHECK(nighres.tasks[i].memory == 4'000'000'000);
  }
  CHECK(nighres.tasks[1].runtime == 614.2867069244385);
  // extract_brain_region lists itself among its "childrens"; the parents make the edges.
  CHECK(nighres.tasks[2].parents == std::vector<std::size_t>{1});
  CHECK(nighres.tasks[3].parents == std::vector<std::size_t>{2});
  CHECK(nighres.warnings == std::vector<std::string>{
                                "nighres_workflow.json: workflow.tasks[3].files[2] (file 'sub001_sess1_left_cerebrum_xproba-lcrgm.nii'): size: "
                                "589824352 bytes here, 98304352 at workflow.tasks[2].files[8], where the file first appears; the first is "
                                "kept, as in WRENCH",
                                "nighres_workflow.json: workflow.tasks[3].files[3] (file 'sub001_sess1_left_cerebrum_xproba-lcrbg.nii'): size: "
                                "589824352 bytes here, 98304352 at workflow.tasks[2].files[11], where the file first appears; the first is "
                                "kept, as in WRENCH",
                                "nighres_workflow.json: workflow.tasks[2] (task 'extract_brain_region'): childrens: lists the task itself, "
                                "and leaves out 'cruise_cortex_extraction', whose parents name this task; ignored: the parents alone make "
                                "the dependencies"});
  const auto lcrgm = std::find_if(nighres.files.begin(), nighres.files.end(),
                                  [](const WfFile& f) { return f.id == "sub001_sess1_left_cerebrum_xproba-lcrgm.nii"; });
  REQUIRE(lcrgm != nighres.files.end());
  CHECK(lcrgm->size == 98'304'352);
}

TEST_CASE("a small workflow reads field by field in both formats", "[scenario][workflow]") {
  const WfWorkflow w = read(small_wfformat().dump());
  CHECK(w.file == "w.json");
  CHECK(w.name == "small");
  CHECK(w.makespan == 10.5);
  CHECK(w.machines == std::vector<std::string>{"m1", "m2"});
  REQUIRE(w.tasks.size() == 2);
  CHECK(w.tasks[0].id == "a");
  CHECK(w.tasks[0].name == "A");
  CHECK(w.tasks[0].runtime == 4.25);
  CHECK(w.tasks[0].cores == 2);
  CHECK(w.tasks[0].memory == 1000);
  CHECK(w.tasks[0].avg_cpu == 150.5);
  CHECK(w.tasks[0].machines == std::vector<std::string>{"m1"});
  CHECK(w.tasks[1].cores == 1);
  CHECK(w.tasks[1].memory == 0);
  CHECK(w.tasks[1].avg_cpu == -1);
  CHECK(w.tasks[1].inputs == std::vector<std::size_t>{1, 0});  // in the order listed
  CHECK(w.tasks[1].outputs == std::vector<std::size_t>{2});
  CHECK(w.warnings.empty());

  const WfWorkflow old = read(small_old_format().dump());
  CHECK(old.format == "WRENCH 2.x (schema before 1.5)");
  REQUIRE(old.tasks.size() == 2);
  CHECK(old.tasks[0].runtime == 1.5);
  CHECK(old.tasks[0].cores == 2);
  CHECK(old.tasks[0].memory == 1000);
  CHECK(old.tasks[1].parents == std::vector<std::size_t>{0});
  CHECK(ids_of(old.tasks[1].inputs, old.files) == std::vector<std::string>{"f2"});
  CHECK(old.files.size() == 3);
  CHECK(total_bytes(old) == 60);
  CHECK(old.warnings.empty());
}

TEST_CASE("WfFormat 1.3 and 1.4 spellings read as the old format", "[scenario][workflow]") {
  const WfWorkflow w = read(R"({"name": "v14", "schemaVersion": "1.4", "workflow": {
      "makespanInSeconds": 30, "machines": [{"nodeName": "n1"}],
      "tasks": [{"name": "t1", "id": "ID01", "runtimeInSeconds": 3, "memoryInBytes": 5e3, "avgCPU": 80, "machine": "n1",
                 "parents": [], "children": [],
                 "files": [{"link": "INPUT", "name": "a.txt", "path": "/data/", "sizeInBytes": 7}]}]}})");
  CHECK(w.format == "WRENCH 2.x (schema before 1.5)");
  CHECK(w.makespan == 30);
  CHECK(w.machines == std::vector<std::string>{"n1"});
  REQUIRE(w.tasks.size() == 1);
  CHECK(w.tasks[0].id == "t1");  // before 1.5 tasks name each other by name
  CHECK(w.tasks[0].runtime == 3);
  CHECK(w.tasks[0].memory == 5000);
  CHECK(w.tasks[0].avg_cpu == 80);
  CHECK(w.tasks[0].machines == std::vector<std::string>{"n1"});
  REQUIRE(w.files.size() == 1);
  CHECK(w.files[0].id == "/data/a.txt");
  CHECK(w.files[0].size == 7);
  CHECK(w.tasks[0].inputs == std::vector<std::size_t>{0});
}

TEST_CASE("children that disagree with the parents are a warning, a child naming no task an error", "[scenario][workflow]") {
  // A task listing itself, as nighres_workflow.json's extract_brain_region does: WRENCH loads
  // it (its old-format reader never reads childrens), so must we.
  json old = small_old_format();
  old["workflow"]["tasks"][1]["childrens"] = {"t2"};
  const WfWorkflow w = read(old.dump());
  CHECK(w.tasks[1].parents == std::vector<std::size_t>{0});
  CHECK(w.tasks[0].parents.empty());
  CHECK(w.warnings == std::vector<std::string>{"w.json: workflow.tasks[1] (task 't2'): childrens: lists the task itself; ignored: the "
                                               "parents alone make the dependencies"});

  json forgotten = small_wfformat();
  forgotten["workflow"]["specification"]["tasks"][0]["children"] = json::array();
  CHECK(read(forgotten.dump()).warnings ==
        std::vector<std::string>{"w.json: workflow.specification.tasks[0] (task 'a'): children: leaves out 'b', whose parents name this task; "
                                 "ignored: the parents alone make the dependencies"});
  json extra = small_wfformat();
  extra["workflow"]["specification"]["tasks"][1]["children"] = {"a"};
  CHECK(read(extra.dump()).warnings ==
        std::vector<std::string>{"w.json: workflow.specification.tasks[1] (task 'b'): children: lists 'a', whose parents do not name this "
                                 "task; ignored: the parents alone make the dependencies"});

  old["workflow"]["tasks"][1]["childrens"] = {"t3"};
  CHECK(error_of_doc(old) == "w.json: workflow.tasks[1] (task 't2'): childrens: unknown task 't3'");
  json typo = small_wfformat();
  typo["workflow"]["specification"]["tasks"][0]["children"] = {"bb"};
  CHECK(error_of_doc(typo) == "w.json: workflow.specification.tasks[0] (task 'a'): children: unknown task 'bb'");
}

TEST_CASE("an old-format file given two sizes keeps the first, with a warning", "[scenario][workflow]") {
  json old = small_old_format();
  old["workflow"]["tasks"][1]["files"][0]["size"] = 25;
  const WfWorkflow w = read(old.dump());
  CHECK(w.files[1].id == "f2");
  CHECK(w.files[1].size == 20);
  CHECK(w.warnings == std::vector<std::string>{"w.json: workflow.tasks[1].files[0] (file 'f2'): size: 25 bytes here, 20 at "
                                               "workflow.tasks[0].files[1], where the file first appears; the first is kept, as in WRENCH"});
}

TEST_CASE("a WfFormat file without an execution section reads with every runtime 0, and says so", "[scenario][workflow]") {
  json doc = small_wfformat();
  doc["workflow"].erase("execution");
  const WfWorkflow w = read(doc.dump());
  CHECK(w.tasks[0].runtime == 0);
  CHECK(w.tasks[0].cores == 1);
  CHECK(w.makespan == -1);
  CHECK(w.machines.empty());
  CHECK(w.warnings ==
        std::vector<std::string>{"w.json: workflow: execution: missing, so nothing was measured: every task's runtime is 0 s"});
}

TEST_CASE("keys the reader does not know change nothing", "[scenario][workflow]") {
  json doc = small_wfformat();
  doc["runtimeSystem"] = {{"name", "Pegasus"}, {"version", "5.0"}};
  doc["workflow"]["specification"]["tasks"][0]["category"] = "split";
  doc["workflow"]["execution"]["tasks"][0]["command"] = {{"program", "x"}, {"arguments", {"a", "b"}}};
  doc["workflow"]["execution"]["tasks"][0]["priority"] = 20;
  doc["workflow"]["execution"]["tasks"][1]["readBytes"] = "not even a number";
  json deep = 1;
  for (int i = 0; i < 100; ++i) deep = json::array({deep});
  doc["workflow"]["execution"]["tasks"][1]["energyInKWh"] = deep;
  const WfWorkflow plain = read(small_wfformat().dump());
  const WfWorkflow noisy = read(doc.dump());
  CHECK(noisy.tasks[0].runtime == plain.tasks[0].runtime);
  CHECK(noisy.tasks[0].machines == plain.tasks[0].machines);
  CHECK(noisy.tasks[1].inputs == plain.tasks[1].inputs);
  CHECK(noisy.files.size() == plain.files.size());
  CHECK(noisy.warnings.empty());
}

TEST_CASE("malformed JSON is refused with the line and column of the fault", "[scenario][workflow]") {
  CHECK(error_of("{\n  \"name\": x\n}") ==
        "w.json:2:11: malformed JSON: syntax error while parsing value - invalid literal; last read: '\"name\": x'");
  CHECK(error_of("[1,2").rfind("w.json:1:5: malformed JSON: syntax error while parsing array - unexpected end of input", 0) == 0);
  CHECK(error_of("").rfind("w.json:1:1: malformed JSON: ", 0) == 0);
  CHECK(error_of("{}\n\n  ]").rfind("w.json:3:3: malformed JSON: ", 0) == 0);
  // A newline inside a string is the fault itself: on the line where the string is (nlohmann's
  // own count says line 2, column 0).
  CHECK(error_of("[\"abc\ndef\"]").rfind("w.json:1:6: malformed JSON: ", 0) == 0);
  // Columns count characters: each é is two bytes.
  CHECK(error_of("\"\xC3\xA9\xC3\xA9\" x").rfind("w.json:1:6: malformed JSON: ", 0) == 0);
  CHECK(error_of("{\"a\": \"\xFF\"}") == "w.json:1:8: malformed JSON: syntax error while parsing value - invalid string: ill-formed UTF-8 "
                                          "byte; last read: '\"\xEF\xBF\xBD'");
  // A number beyond a double: nlohmann's document parser gives no position for it.
  CHECK(error_of("{\"a\":\n [1e400]}") == "w.json:2:7: malformed JSON: number overflow parsing '1e400'");
  // A long unterminated string is not quoted whole.
  const std::string message = error_of("[\"" + std::string(100'000, 'x'));
  CHECK(message.rfind("w.json:1:100003: malformed JSON: ", 0) == 0);
  CHECK(message.size() < 300);
}

TEST_CASE("a key twice in one object is refused at the second, whatever its spelling; in two objects it is two keys", "[scenario][workflow]") {
  // As the issue found them: the workflow's name, a file's size (the last would have won).
  std::string names = small_wfformat().dump(2);
  names.replace(names.find("\"name\": \"small\""), 15, "\"name\": \"w\", \"name\": \"v\"");
  CHECK_THAT(error_of(names), Catch::Matches("w\\.json:[0-9]+:[0-9]+: key \"name\" appears twice in one object .*"));
  std::string sizes = small_wfformat().dump();
  sizes.replace(sizes.find("\"sizeInBytes\":100"), 17, "\"sizeInBytes\":1000000,\"sizeInBytes\":5");
  CHECK_THAT(error_of(sizes), Catch::Contains("key \"sizeInBytes\" appears twice in one object"));
  // Line and column of the second.
  CHECK_THAT(error_of("{\"a\": 1,\n  \"a\": 2}"), Catch::StartsWith("w.json:2:3: key \"a\" appears twice"));
  // One key spelt with an escape, deep inside arrays, after a string holding braces and quotes.
  CHECK_THAT(error_of(R"({"x": [[{"s": "{\"k\": [", "k": 1, "\u006b": 2}]]})"), Catch::StartsWith("w.json:1:36: key \"k\" appears twice"));
  // Keys of sibling and nested objects, and strings equal to a key as values, are no repeats.
  const json plain = small_wfformat();
  json doc = plain;
  doc["workflow"]["execution"]["tasks"][0]["name"] = "name";
  doc["note"] = {{"name", {{"name", 1}}}};
  CHECK_NOTHROW(read(doc.dump()));
  CHECK_NOTHROW(check_unique_keys(R"([{"a": 1}, {"a": 2}, {"b": {"a": 3}, "a": 4}])", "x.json"));
}

TEST_CASE("deep nesting is refused at the first bracket too deep, before any document is built", "[scenario][workflow]") {
  CHECK(error_of(std::string(1'000'000, '[')) ==
        "w.json:1:129: JSON nested deeper than 128 levels of arrays and objects (a workflow needs fewer than 10)");
  CHECK(error_of(std::string(1'000'000, '[') + std::string(1'000'000, ']')).rfind("w.json:1:129: JSON nested deeper", 0) == 0);
  CHECK(error_of("{\"a\": \"[[[[\",\n" + std::string(200, '{')).rfind("w.json:2:128: JSON nested deeper", 0) == 0);  // brackets in strings do not count
  // 128 levels are read (and refused for what they are).
  CHECK(error_of(std::string(128, '[') + std::string(128, ']')) ==
        "w.json: expected a JSON object (a workflow instance) at the top level, got an array");
}

TEST_CASE("the format is told by schemaVersion, and an unknown one is refused by name", "[scenario][workflow]") {
  json doc = small_wfformat();
  doc["schemaVersion"] = "1.6";
  CHECK(read(doc.dump()).format == "WfFormat 1.6");
  doc["schemaVersion"] = "1.7";
  CHECK(error_of_doc(doc) == "w.json: schemaVersion: '1.7' is not a version this reader knows: it reads WfFormat 1.5 and 1.6, and the format "
                         "before it (workflow.tasks, with no schemaVersion or 1.0 to 1.4)");
  doc["schemaVersion"] = 1.5;
  CHECK(error_of_doc(doc) == "w.json: schemaVersion: expected a string such as \"1.5\", got a number");
  doc.erase("schemaVersion");
  CHECK(error_of_doc(doc).rfind("w.json: schemaVersion: missing, and no workflow.tasks either", 0) == 0);
  json old = small_old_format();
  old["schemaVersion"] = "1.2";
  CHECK(read(old.dump()).format == "WRENCH 2.x (schema before 1.5)");
  old["workflow"]["jobs"] = old["workflow"]["tasks"];
  old["workflow"].erase("tasks");
  CHECK(error_of_doc(old).rfind("w.json: schemaVersion: '1.2' files list their tasks in workflow.tasks, and this one has none (1.0 to 1.2 "
                            "wrote workflow.jobs",
                            0) == 0);
  old["schemaVersion"] = "1.5";
  CHECK(error_of_doc(old) == "w.json: workflow: specification: missing: WfFormat 1.5 keeps the tasks and files in workflow.specification");
  CHECK(error_of("[]") == "w.json: expected a JSON object (a workflow instance) at the top level, got an array");
}

TEST_CASE("each broken WfFormat field is refused naming the file, the path and the key", "[scenario][workflow]") {
  struct Case {
    json::json_pointer at;
    json value;  // null: the key is removed
    std::string message;
  };
  const std::string file1 = "w.json: workflow.specification.files[1] (file 'mid'): ";
  const std::string task1 = "w.json: workflow.specification.tasks[1] (task 'b'): ";
  const std::string record0 = "w.json: workflow.execution.tasks[0] (task 'a'): ";
  const std::vector<Case> cases = {
      {"/workflow/specification/files/1/sizeInBytes"_json_pointer, "200", file1 + "sizeInBytes: expected a whole number of bytes, got a string"},
      {"/workflow/specification/files/1/sizeInBytes"_json_pointer, -1, file1 + "sizeInBytes: must not be negative, got -1"},
      {"/workflow/specification/files/1/sizeInBytes"_json_pointer, 2.5, file1 + "sizeInBytes: must be a whole number, got 2.5"},
      {"/workflow/specification/files/1/sizeInBytes"_json_pointer, (std::uint64_t{1} << 60) + 1,
       file1 + "sizeInBytes: 1152921504606846977 bytes is too large (at most 2^60, 1 EiB)"},
      {"/workflow/specification/files/1/sizeInBytes"_json_pointer, 1e300, file1 + "sizeInBytes: 1e+300 bytes is too large (at most 2^60, 1 EiB)"},
      {"/workflow/specification/files/1/sizeInBytes"_json_pointer, nullptr, file1 + "sizeInBytes: missing: every file needs its size in bytes"},
      {"/workflow/specification/files/1/id"_json_pointer, nullptr, "w.json: workflow.specification.files[1]: id: missing: every file needs an id"},
      {"/workflow/specification/files/1/id"_json_pointer, "", "w.json: workflow.specification.files[1]: id: must not be empty"},
      {"/workflow/specification/files/1/id"_json_pointer, "in", "w.json: workflow.specification.files[1] (file 'in'): id: a second file 'in': "
                                                                "the first is files[0]"},
      {"/workflow/specification/files/1"_json_pointer, "mid", "w.json: workflow.specification.files[1]: expected an object, got a string"},
      {"/workflow/specification/files"_json_pointer, json::object(), "w.json: workflow.specification: files: expected an array, got an object"},
      {"/workflow/specification/tasks/1/id"_json_pointer, 5, "w.json: workflow.specification.tasks[1]: id: expected a string, got a number"},
      {"/workflow/specification/tasks/1/id"_json_pointer, "a", "w.json: workflow.specification.tasks[1] (task 'a'): id: a second task 'a': "
                                                               "the first is tasks[0]"},
      {"/workflow/specification/tasks/1/parents"_json_pointer, {"zz"}, task1 + "parents: unknown task 'zz'"},
      {"/workflow/specification/tasks/1/parents"_json_pointer, {"b"}, task1 + "parents: lists the task itself"},
      {"/workflow/specification/tasks/1/parents"_json_pointer, "a", task1 + "parents: expected an array, got a string"},
      {"/workflow/specification/tasks/1/parents"_json_pointer, {"a", 7}, task1 + "parents: item 1 is a number, expected a task id (a string)"},
      {"/workflow/specification/tasks/1/inputFiles"_json_pointer, {"mid", "nope"}, task1 + "inputFiles: unknown file 'nope'"},
      {"/workflow/specification/tasks/1/outputFiles"_json_pointer, {""}, task1 + "outputFiles: item 0 is an empty string, expected a file id"},
      {"/workflow/specification/tasks"_json_pointer, json::array(), "w.json: workflow.specification: tasks: empty: a workflow needs at least one task"},
      {"/workflow/specification/tasks/0"_json_pointer, 7, "w.json: workflow.specification.tasks[0]: expected an object, got a number"},
      {"/workflow/specification/tasks"_json_pointer, nullptr, "w.json: workflow.specification: tasks: missing: the workflow's tasks"},
      {"/workflow/execution/tasks/0/runtimeInSeconds"_json_pointer, -1, record0 + "runtimeInSeconds: must not be negative, got -1"},
      {"/workflow/execution/tasks/0/runtimeInSeconds"_json_pointer, "4", record0 + "runtimeInSeconds: expected a number, got a string"},
      {"/workflow/execution/tasks/0/runtimeInSeconds"_json_pointer, 2e9, record0 + "runtimeInSeconds: must be between 0 and 1000000000, got 2000000000.0"},
      {"/workflow/execution/tasks/0/runtimeInSeconds"_json_pointer, nullptr, record0 + "runtimeInSeconds: missing: the task's measured runtime in seconds"},
      {"/workflow/execution/tasks/0/coreCount"_json_pointer, 0, record0 + "coreCount: must be between 1 and 1000000, got 0"},
      {"/workflow/execution/tasks/0/coreCount"_json_pointer, 2'000'000, record0 + "coreCount: must be between 1 and 1000000, got 2000000"},
      {"/workflow/execution/tasks/0/coreCount"_json_pointer, 1.5, record0 + "coreCount: must be a whole number, got 1.5"},
      {"/workflow/execution/tasks/0/coreCount"_json_pointer, true, record0 + "coreCount: expected a whole number, got a boolean"},
      {"/workflow/execution/tasks/0/memoryInBytes"_json_pointer, -5, record0 + "memoryInBytes: must not be negative, got -5"},
      {"/workflow/execution/tasks/0/avgCPU"_json_pointer, -3.5, record0 + "avgCPU: must not be negative, got -3.5"},
      {"/workflow/execution/tasks/0/machines"_json_pointer, {"m3"}, record0 + "machines: unknown machine 'm3' (not in workflow.execution.machines)"},
      {"/workflow/execution/tasks/1/id"_json_pointer, "zz", "w.json: workflow.execution.tasks[1] (task 'zz'): id: no task 'zz' in "
                                                            "workflow.specification.tasks"},
      {"/workflow/execution/tasks/1/id"_json_pointer, "a", "w.json: workflow.execution.tasks[1] (task 'a'): id: a second record for task 'a': "
                                                           "the first is tasks[0]"},
      {"/workflow/execution/tasks/1"_json_pointer, nullptr, task1 + "id: no record in workflow.execution.tasks, so no runtime (a file without "
                                                                    "an execution section reads as a specification, every runtime 0 s)"},
      {"/workflow/execution/machines/1/nodeName"_json_pointer, "m1", "w.json: workflow.execution.machines[1] (machine 'm1'): nodeName: a "
                                                                     "second machine 'm1': the first is machines[0]"},
      {"/workflow/execution/makespanInSeconds"_json_pointer, -1, "w.json: workflow.execution: makespanInSeconds: must not be negative, got -1"},
      {"/workflow/execution"_json_pointer, json::array(), "w.json: workflow: execution: expected an object, got an array"},
      {"/name"_json_pointer, 3, "w.json: name: expected a string, got a number"},
  };
  for (const Case& c : cases) {
    json doc = small_wfformat();
    if (c.value.is_null()) remove(doc, c.at);
    else doc[c.at] = c.value;
    INFO(c.at.to_string() << " = " << c.value.dump());
    CHECK(error_of_doc(doc) == c.message);
  }
}

TEST_CASE("a task without an id takes its name, and whole numbers written as 2.0 are whole", "[scenario][workflow]") {
  json doc = small_wfformat();
  doc["workflow"]["specification"]["tasks"][1].erase("id");
  doc["workflow"]["specification"]["tasks"][1]["name"] = "b";
  doc["workflow"]["specification"]["files"][1]["sizeInBytes"] = 2e3;
  doc["workflow"]["execution"]["tasks"][0]["coreCount"] = 4.0;
  doc["workflow"]["execution"]["tasks"][0]["memoryInBytes"] = 1000.6;  // any number, rounded
  const WfWorkflow w = read(doc.dump());
  CHECK(w.tasks[1].id == "b");
  CHECK(w.files[1].size == 2000);
  CHECK(w.tasks[0].cores == 4);
  CHECK(w.tasks[0].memory == 1001);
  doc["workflow"]["specification"]["tasks"][1].erase("name");
  CHECK(error_of_doc(doc) == "w.json: workflow.specification.tasks[1]: id: missing: every task needs an id");
}

TEST_CASE("each broken old-format field is refused naming the file, the path and the key", "[scenario][workflow]") {
  struct Case {
    json::json_pointer at;
    json value;
    std::string message;
  };
  const std::string t2 = "w.json: workflow.tasks[1] (task 't2'): ";
  const std::string f1 = "w.json: workflow.tasks[0].files[0] (file 'f1'): ";
  const std::vector<Case> cases = {
      {"/workflow/tasks/1/runtime"_json_pointer, nullptr, t2 + "runtime: missing: the task's runtime in seconds"},
      {"/workflow/tasks/1/runtimeInSeconds"_json_pointer, 2, t2 + "runtime: given together with 'runtimeInSeconds': give one of them"},
      {"/workflow/tasks/1/runtime"_json_pointer, -0.5, t2 + "runtime: must not be negative, got -0.5"},
      {"/workflow/tasks/1/cores"_json_pointer, 0, t2 + "cores: must be between 1 and 1000000, got 0"},
      {"/workflow/tasks/1/memory"_json_pointer, "4 GB", t2 + "memory: expected a number, got a string"},
      {"/workflow/tasks/1/parents"_json_pointer, {"t0"}, t2 + "parents: unknown task 't0'"},
      {"/workflow/tasks/1/name"_json_pointer, "t1", "w.json: workflow.tasks[1] (task 't1'): name: a second task 't1': the first is tasks[0]"},
      {"/workflow/tasks/1/name"_json_pointer, nullptr, "w.json: workflow.tasks[1]: name: missing: every task needs a name, by which its "
                                                       "children name it"},
      {"/workflow/tasks/1/machine"_json_pointer, "n9", t2 + "machine: unknown machine 'n9' (not in workflow.machines)"},
      {"/workflow/tasks/0/files/0/link"_json_pointer, "inout", f1 + "link: expected \"input\" or \"output\", got 'inout'"},
      {"/workflow/tasks/0/files/0/link"_json_pointer, nullptr, f1 + "link: missing: \"input\" or \"output\""},
      {"/workflow/tasks/0/files/0/size"_json_pointer, nullptr, f1 + "size: missing: every file needs its size in bytes"},
      {"/workflow/tasks/0/files/0/size"_json_pointer, -10, f1 + "size: must not be negative, got -10"},
      {"/workflow/tasks/0/files/0/name"_json_pointer, nullptr, "w.json: workflow.tasks[0].files[0]: name: missing: every file needs its name"},
      {"/workflow/tasks/0/files"_json_pointer, {"f1"}, "w.json: workflow.tasks[0].files[0]: expected an object, got a string"},
      {"/workflow/tasks"_json_pointer, json::array(), "w.json: workflow: tasks: empty: a workflow needs at least one task"},
      {"/workflow/makespan"_json_pointer, "long", "w.json: workflow: makespan: expected a number, got a string"},
  };
  for (const Case& c : cases) {
    json doc = small_old_format();
    doc["workflow"]["machines"] = json::array({{{"nodeName", "n1"}}});
    if (c.value.is_null()) remove(doc, c.at);
    else doc[c.at] = c.value;
    INFO(c.at.to_string() << " = " << c.value.dump());
    CHECK(error_of_doc(doc) == c.message);
  }
}

// A chain in which each task's parent comes after it, so that a depth-first search from the
// first task goes n deep: task i has parent i + 1.
json chain(std::size_t n, bool closed) {
  json tasks = json::array();
  for (std::size_t i = 0; i < n; ++i) {
    json parents = json::array();
    if (i + 1 < n) parents.push_back(fmt::format("t{}", i + 1));
    else if (closed) parents.push_back("t0");
    tasks.push_back({{"id", fmt::format("t{}", i)}, {"parents", parents}});
  }
  return {{"schemaVersion", "1.5"}, {"workflow", {{"specification", {{"tasks", tasks}}}}}};
}

TEST_CASE("a dependency cycle is refused naming its tasks, and 10^5 tasks in a chain need no deep stack", "[scenario][workflow]") {
  json doc = small_wfformat();
  doc["workflow"]["specification"]["tasks"][0]["parents"] = {"b"};
  CHECK(error_of_doc(doc) == "w.json: workflow.specification.tasks[0] (task 'a'): parents: dependency cycle: 'a' -> 'b' -> 'a' (each task "
                         "lists the next among its parents)");

  const WfWorkflow long_chain = read(chain(100'000, false).dump());
  REQUIRE(long_chain.tasks.size() == 100'000);
  CHECK(long_chain.tasks[99'998].parents == std::vector<std::size_t>{99'999});
  CHECK(error_of_doc(chain(100'000, true)) ==
        "w.json: workflow.specification.tasks[0] (task 't0'): parents: dependency cycle: 't0' -> 't1' -> 't2' -> 't3' -> 't4' -> 't5' -> 't6' "
        "-> 't7' -> ... (100000 tasks in all) -> 't0' (each task lists the next among its parents)");
  json old = small_old_format();
  old["workflow"]["tasks"][0]["parents"] = {"t2"};
  CHECK(error_of_doc(old) == "w.json: workflow.tasks[0] (task 't1'): parents: dependency cycle: 't1' -> 't2' -> 't1' (each task lists the next "
                         "among its parents)");
}

TEST_CASE("a hostile file is bounded by the limits on tasks and files, naming the count", "[scenario][workflow]") {
  // 10^6 tasks: refused on the count, before any task is read.
  std::string tasks = "{\"workflow\": {\"tasks\": [{}";
  for (int i = 1; i < 1'000'000; ++i) tasks += ",{}";
  tasks += "]}}";
  CHECK(error_of(tasks, 10'000) == "w.json: workflow: tasks: 1000000 tasks, more than the limit of 10000");
  json doc = small_wfformat();
  CHECK(error_of(doc.dump(), 1) == "w.json: workflow.specification: tasks: 2 tasks, more than the limit of 1");
  CHECK(error_of(doc.dump(), 10, 2) == "w.json: workflow.specification: files: 3 files, more than the limit of 2");
  CHECK(read(doc.dump(), 2, 3).tasks.size() == 2);
  doc["workflow"]["execution"]["tasks"].push_back({{"id", "c"}, {"runtimeInSeconds", 1}});
  CHECK(error_of(doc.dump(), 2) == "w.json: workflow.execution: tasks: 3 tasks, more than the limit of 2");
  // The old format meets its files one by one.
  CHECK(error_of(small_old_format().dump(), 10, 2) ==
        "w.json: workflow.tasks[1].files[1] (file 'f3'): name: 3 distinct files, more than the limit of 2");
  // Repeats cost a step each: 10^6 mentions of one parent make one parent.
  json repeats = small_wfformat();
  repeats["workflow"]["specification"]["tasks"][1]["parents"] = std::vector<std::string>(1'000'000, "a");
  CHECK(read(repeats.dump()).tasks[1].parents == std::vector<std::size_t>{0});
}

TEST_CASE("names in messages are quoted visibly and cut short", "[scenario][workflow]") {
  json doc = small_wfformat();
  doc["workflow"]["specification"]["tasks"][1]["parents"] = {"\x1b[2Jzz\n"};
  CHECK(error_of_doc(doc) == "w.json: workflow.specification.tasks[1] (task 'b'): parents: unknown task '\\u001b[2Jzz\\n'");
  doc["workflow"]["specification"]["tasks"][1]["parents"] = {std::string(5000, 'y')};
  CHECK(error_of_doc(doc) == "w.json: workflow.specification.tasks[1] (task 'b'): parents: unknown task '" + std::string(100, 'y') +
                             "...' (5000 bytes)");
}

TEST_CASE("warnings stop at a hundred, the last saying how many more there were", "[scenario][workflow]") {
  json old = small_old_format();
  json& files = old["workflow"]["tasks"][1]["files"];
  for (int i = 0; i < 150; ++i) files.push_back({{"link", "input"}, {"name", "f1"}, {"size", 11 + i}});
  const WfWorkflow w = read(old.dump());
  REQUIRE(w.warnings.size() == kMaxWorkflowWarnings);
  CHECK(w.warnings[98].rfind("w.json: workflow.tasks[1].files[100] (file 'f1'): size: 109 bytes here, 10 at", 0) == 0);
  CHECK(w.warnings.back() == "w.json: 51 more warnings, not shown");
  CHECK(w.tasks[1].inputs == std::vector<std::size_t>{1, 0});
}

TEST_CASE("the fuzz target's contract holds for the reference workflows, the seeds and hostile inputs", "[scenario][workflow][fuzz]") {
  std::vector<std::filesystem::path> inputs;
  for (const auto& dir : {kInputs / "wfcommons" / "instances", kInputs / "wrench-cache",
                          std::filesystem::path(PAGECACHE_FUZZ_SEEDS_DIR)}) {
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
      if (entry.path().extension() == ".json") inputs.push_back(entry.path());
    }
  }
  REQUIRE(inputs.size() == 13);
  for (const auto& path : inputs) {
    INFO(path.string());
    const std::string text = testing::slurp(path);
    CHECK(fuzz::check_workflow_text(text, path.string()).empty());
    CHECK_NOTHROW(read_workflow_json(text, path.string(), fuzz::kFuzzMaxTasks, fuzz::kFuzzMaxFiles));  // read, not refused
  }
  for (const std::string& hostile : {std::string(1'000'000, '['), std::string("{\"a\": 1e400}"), chain(5'000, true).dump(),
                                     std::string("{\"workflow\": {\"tasks\": [") + std::string(200'000, '{')}) {
    CHECK(fuzz::check_workflow_text(hostile, "fuzz.json").empty());
  }
}

TEST_CASE("the fuzz target's property check catches each broken promise", "[scenario][workflow][fuzz]") {
  const WfWorkflow good = read(small_wfformat().dump());
  REQUIRE(fuzz::workflow_problem(good).empty());
  WfWorkflow w = good;
  w.tasks[0].parents = {1};
  CHECK(fuzz::workflow_problem(w) == "the parents form a cycle");
  w = good;
  w.tasks[1].parents = {2};
  CHECK(fuzz::workflow_problem(w) == "parent index 2 out of range in task b");
  w = good;
  w.tasks[1].inputs = {0, 0};
  CHECK(fuzz::workflow_problem(w) == "input index 0 repeated in task b");
  w = good;
  w.files[1].id = "in";
  CHECK(fuzz::workflow_problem(w) == "file id empty or repeated: in");
  w = good;
  w.tasks[0].machines = {"m9"};
  CHECK(fuzz::workflow_problem(w) == "unknown machine in task a");
  w = good;
  w.tasks[0].cores = 0;
  CHECK(fuzz::workflow_problem(w) == "cores out of range: a");
}


// A workflow of tasks on the recorded machines' platform, run from pcsim's options
// (load_workflow): what the options give wrong names the option, what the instance gives wrong
// names its file and task, never the scenario document the options make.
TEST_CASE("a workflow run from pcsim's options names the option at fault, or the workflow file and its task", "[scenario][workflow]") {
  const std::filesystem::path dir = testing::scratch("workflow-options");
  const std::string platform = (std::filesystem::path(PCSIM_SOURCE_DIR) / "platforms/wfcommons-chameleon.xml").string();
  // Tasks `tasks` ({id, outputs, cores, machine}) writing file x, with their records.
  const auto write = [&](const std::string& name, const json& tasks) {
    json doc = small_wfformat();
    json& spec = doc["workflow"]["specification"];
    json& records = doc["workflow"]["execution"]["tasks"];
    spec["tasks"] = json::array();
    records = json::array();
    spec["files"] = json::array({{{"id", "x"}, {"sizeInBytes", 1000}}});
    doc["workflow"]["execution"]["machines"] = json::array({{{"nodeName", "compute-3"}}, {{"nodeName", "pegasus-5"}}});
    for (const json& t : tasks) {
      const bool writes = t[1].get<bool>();
      spec["tasks"].push_back({{"id", t[0]}, {"parents", json::array()}, {"inputFiles", writes ? json::array() : json::array({"x"})},
                               {"outputFiles", writes ? json::array({"x"}) : json::array()}});
      records.push_back({{"id", t[0]}, {"runtimeInSeconds", 1}, {"coreCount", t[2]}, {"machines", json::array({t[3]})}});
    }
    const std::string path = (dir / name).string();
    std::ofstream(path) << doc.dump();
    return path;
  };
  const auto options = [&](const std::string& on, const std::string& files_host = {}, const std::vector<std::string>& hosts = {}) {
    WorkflowOptions o;
    o.platform = on;
    o.files_host = files_host;
    o.hosts = hosts;
    return o;
  };
  const auto error_of_run = [](const std::string& workflow, const WorkflowOptions& o) -> std::string {
    try {
      load_workflow(workflow, o);
    } catch (const ConfigError& e) {
      return e.what();
    }
    return "(loaded)";
  };
  const std::string fine = write("fine.json", json::array({{"a", true, 1, "compute-3"}, {"b", false, 1, "compute-3"}}));
  REQUIRE(load_workflow(fine, options(platform)).workflows.at(0).tasks.size() == 2);
  CHECK(error_of_run(fine, options(platform, "nowhere")) ==
        "--files-host nowhere: key 'workflow.files_host': no host named 'nowhere'");
  CHECK(error_of_run(fine, options(platform, {}, {"compute-3", "nowhere"})) ==
        "--hosts compute-3,nowhere: key 'workflow.hosts': no host named 'nowhere'");
  // A --platform that cannot be read is refused before a document is made around it.
  CHECK(error_of_run(fine, options((dir / "none.xml").string())) ==
        fmt::format("--platform {}: cannot open the platform file: No such file or directory", (dir / "none.xml").string()));

  // The instance's own faults: two tasks writing one file, a task needing more cores than its
  // machine has, a task on a machine its file's host has no route to.
  const std::string twice = write("twice.json", json::array({{"a", true, 1, "compute-3"}, {"b", true, 1, "compute-3"}}));
  CHECK(error_of_run(twice, options(platform)) == twice + ": task 'b': file 'x' is written by two tasks, 'a' and 'b'");
  const std::string wide = write("wide.json", json::array({{"a", true, 1000, "compute-3"}}));
  CHECK(error_of_run(wide, options(platform)) == wide + ": task 'a': needs 1000 cores, more than its host 'compute-3' has (48)");
  const std::string apart = write("apart.json", json::array({{"a", true, 1, "pegasus-5"}, {"b", false, 1, "compute-3"}}));
  CHECK(error_of_run(apart, options(platform)) ==
        apart + ": workflow 'small', task 'a': file 'x' is on host 'compute-3', and no link or route joins it to 'pegasus-5'");
  // The same from a scenario file's [workflow] table.
  std::ofstream(dir / "s.toml") << fmt::format("platform = \"{}\"\nworkflow = \"wide.json\"\n", platform);
  CHECK_THROWS_WITH(load_scenario((dir / "s.toml").string()), wide + ": task 'a': needs 1000 cores, more than its host 'compute-3' has (48)");
}

}  // namespace
}  // namespace pagecache::scenario
