// pcsim run on inputs made by others (issue 16): WfCommons instances in WfFormat 1.5 and
// WRENCH-cache's own inputs as they are, SimGrid's platform examples, and broken ones.

#include "support/files.hpp"
#include "support/pcsim_cli.hpp"

#include <catch2/catch.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using pagecache::testing::pcsim;
using pagecache::testing::scratch;
using pagecache::testing::slurp;

namespace {

const fs::path kInputs = PAGECACHE_INPUTS_DIR;
const fs::path kSource = PCSIM_SOURCE_DIR;

// A CSV file's rows, fields split as RFC 4180 says (quoted fields may hold commas and quotes).
std::vector<std::vector<std::string>> csv_rows(const std::string& text) {
  std::vector<std::vector<std::string>> rows(1);
  std::string field;
  bool quoted = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') field += '"', ++i;
      else if (c == '"') quoted = false;
      else field += c;
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      rows.back().push_back(field), field.clear();
    } else if (c == '\n') {
      rows.back().push_back(field), field.clear();
      rows.emplace_back();
    } else if (c != '\r') {
      field += c;
    }
  }
  if (rows.back().empty()) rows.pop_back();
  return rows;
}

struct Phase {
  double start = 0, end = 0;
  std::int64_t bytes = 0;
  std::string host;  // where the task ran
};

// timeline.csv by task, then phase.
std::map<std::string, std::map<std::string, Phase>> timeline(const fs::path& out) {
  std::map<std::string, std::map<std::string, Phase>> tasks;
  const auto rows = csv_rows(slurp(out / "timeline.csv"));
  REQUIRE(rows.size() > 1);
  CHECK(rows[0] == std::vector<std::string>{"app", "task", "host", "phase", "start_s", "end_s", "bytes", "cache_bytes", "disk_bytes"});
  for (std::size_t i = 1; i < rows.size(); ++i) {
    REQUIRE(rows[i].size() == 9);
    tasks[rows[i][1]][rows[i][3]] = {std::stod(rows[i][4]), std::stod(rows[i][5]), std::stoll(rows[i][6]), rows[i][2]};
  }
  return tasks;
}

double summary_number(const fs::path& out, const std::string& key) {
  const nlohmann::json summary = nlohmann::json::parse(slurp(out / "summary.json"));
  return summary.at(key).get<double>();
}

}  // namespace

TEST_CASE("each WfCommons instance runs on the shipped Chameleon platform: parents first, every file's bytes moved",
          "[cli][inputs][wfcommons]") {
  const fs::path platform = kSource / "platforms" / "wfcommons-chameleon.xml";
  std::vector<fs::path> instances;
  for (const auto& entry : fs::directory_iterator(kInputs / "wfcommons" / "instances")) instances.push_back(entry.path());
  std::sort(instances.begin(), instances.end());
  REQUIRE(instances.size() == 8);
  for (const fs::path& instance : instances) {
    INFO(instance.filename().string());
    const fs::path out = scratch("wfcommons-" + instance.stem().string()) / "out";
    const auto run = pcsim(fmt::format("run '{}' --platform '{}' --out '{}' --quiet", instance.string(), platform.string(), out.string()));
    INFO(run.output);
    REQUIRE(run.status == 0);

    // What the instance says, read here with nlohmann, not with pcsim's reader.
    const nlohmann::json wf = nlohmann::json::parse(slurp(instance)).at("workflow");
    std::map<std::string, std::int64_t> size;
    for (const auto& f : wf.at("specification").at("files")) size[f.at("id").get<std::string>()] = f.at("sizeInBytes").get<std::int64_t>();
    const auto tasks = timeline(out);
    REQUIRE(tasks.size() == wf.at("specification").at("tasks").size());
    for (const auto& t : wf.at("specification").at("tasks")) {
      const std::string id = t.at("id").get<std::string>();
      INFO("task " << id);
      REQUIRE(tasks.count(id) == 1);
      const auto& phases = tasks.at(id);
      std::int64_t in = 0, out_bytes = 0;
      for (const auto& f : t.at("inputFiles")) in += size.at(f.get<std::string>());
      for (const auto& f : t.at("outputFiles")) out_bytes += size.at(f.get<std::string>());
      CHECK(phases.at("read").bytes == in);
      CHECK(phases.at("write").bytes == out_bytes);
      for (const auto& parent : t.at("parents")) {
        CHECK(phases.at("read").start >= tasks.at(parent.get<std::string>()).at("write").end);
      }
    }
  }
}

TEST_CASE("a WfCommons instance runs where it ran: tasks on their recorded machines, files on the first", "[cli][inputs][wfcommons]") {
  // blast ran on two VMs: its files live on the first, the tasks of the second reach them over
  // the platform's route, so the link carries what those tasks read and write.
  const fs::path out = scratch("blast-two-machines") / "out";
  const auto run = pcsim(fmt::format("run '{}' --platform '{}' --out '{}' --quiet",
                                     (kInputs / "wfcommons" / "instances" / "blast-chameleon-small-001.json").string(),
                                     (kSource / "platforms" / "wfcommons-chameleon.xml").string(), out.string()));
  INFO(run.output);
  REQUIRE(run.status == 0);
  const auto shown = pcsim(fmt::format("show '{}' --platform '{}'", (kInputs / "wfcommons" / "instances" / "blast-chameleon-small-001.json").string(),
                                       (kSource / "platforms" / "wfcommons-chameleon.xml").string()));
  REQUIRE(shown.status == 0);
  CHECK_THAT(shown.output, Catch::Contains("hosts = [ \"worker-1.novalocal\", \"worker-2.novalocal\" ]"));
  CHECK_THAT(shown.output, Catch::Contains("host = \"worker-2.novalocal\""));
  CHECK_THAT(shown.output, Catch::Contains("[[routes]]\nhosts = [ \"worker-2.novalocal\", \"worker-1.novalocal\" ]\nlinks = [ \"blast-network\" ]"));
  // The other machines of the platform take no part.
  CHECK_THAT(shown.output, !Catch::Contains("pegasus-5"));
}

namespace {

// The phases of `a` and `b` whose durations differ by more than 0.1 % (or whose bytes differ).
std::set<std::string> differing_phases(const fs::path& a_out, const fs::path& b_out) {
  const auto a = timeline(a_out);
  const auto b = timeline(b_out);
  REQUIRE(a.size() == b.size());
  std::set<std::string> differ;
  for (const auto& [task, phases] : b) {
    REQUIRE(a.count(task) == 1);
    for (const auto& [phase, row] : phases) {
      const Phase& other = a.at(task).at(phase);
      const double seconds = row.end - row.start;
      if (std::abs((other.end - other.start) - seconds) > 0.001 * seconds + 1e-6 || other.bytes != row.bytes) differ.insert(task + " " + phase);
    }
  }
  return differ;
}

}  // namespace

TEST_CASE("nighres_workflow.json on single_host.xml runs as the paper's Exp 4 scenario, but where the two inputs differ",
          "[cli][inputs][wrench]") {
  // WRENCH-cache's nighres_workflow.json is not quite the workflow the paper simulated (the
  // paper's Nighres parameters, which scenarios/paper/exp4.toml holds): extract_brain_region
  // reads sub001_sess1_strip-{seg,dist,lbls,mems}.nii, which no task writes (so they come from
  // the disk), where the paper's reads mgdm_segmentation's outputs from the cache; and
  // cruise_cortex_extraction writes eight files of 589824352 bytes, not 98304352. Exactly those
  // two phases differ; corrected on those two points, the JSON gives exp4.toml's phase times.
  const fs::path dir = scratch("nighres-vs-exp4");
  const fs::path original = kSource / "inputs" / "wrench-cache" / "nighres_workflow.json";
  const std::string platform = (kSource / "inputs" / "wrench-cache" / "single_host.xml").string();
  nlohmann::json corrected = nlohmann::json::parse(slurp(original));
  for (auto& task : corrected["workflow"]["tasks"]) {
    for (auto& file : task["files"]) {
      std::string name = file["name"].get<std::string>();
      if (task["name"] == "extract_brain_region" && file["link"] == "input") name.replace(name.find("strip"), 5, "mgdm");
      file["name"] = name;
      if (task["name"] == "cruise_cortex_extraction") file["size"] = 98304352;
    }
  }
  std::ofstream(dir / "corrected.json") << corrected.dump(2);

  const auto toml = pcsim(fmt::format("run '{}' --profile paper --out '{}' --quiet", (kSource / "scenarios" / "paper" / "exp4.toml").string(),
                                      (dir / "toml").string()));
  REQUIRE(toml.status == 0);
  for (const auto& [json, out] : {std::pair{original, dir / "json"}, std::pair{dir / "corrected.json", dir / "corrected"}}) {
    const auto run = pcsim(fmt::format("run '{}' --platform '{}' --profile paper --out '{}' --quiet", json.string(), platform, out.string()));
    INFO(run.output);
    REQUIRE(run.status == 0);
  }
  CHECK(differing_phases(dir / "json", dir / "toml") == std::set<std::string>{"extract_brain_region read", "cruise_cortex_extraction write"});
  CHECK(differing_phases(dir / "corrected", dir / "toml").empty());
  CHECK(std::abs(summary_number(dir / "corrected", "makespan_s") - summary_number(dir / "toml", "makespan_s")) <=
        0.001 * summary_number(dir / "toml", "makespan_s"));
}

TEST_CASE("two_hosts.xml runs a workflow over NFS: files on the storage host, tasks on the compute host", "[cli][inputs][wrench]") {
  const fs::path out = scratch("two-hosts-nfs") / "out";
  const auto run = pcsim(fmt::format("run '{}' --platform '{}' --files-host storage_host --out '{}' --quiet",
                                     (kSource / "inputs" / "wrench-cache" / "nighres_workflow.json").string(),
                                     (kSource / "inputs" / "wrench-cache" / "two_hosts.xml").string(), out.string()));
  INFO(run.output);
  REQUIRE(run.status == 0);
  // The compute host's cache holds what its tasks read (an NFS client's), the storage host's
  // memory rows are there too: both hosts took part.
  const std::string memory = slurp(out / "memory.csv");
  CHECK_THAT(memory, Catch::Contains("compute_host"));
  CHECK_THAT(memory, Catch::Contains("storage_host"));
  // The first task read its three inputs from the server's disk (nothing cached at start).
  const auto tasks = timeline(out);
  const auto rows = csv_rows(slurp(out / "timeline.csv"));
  const auto first_read = std::find_if(rows.begin(), rows.end(), [](const auto& r) { return r[1] == "mp2rage_skullstripping" && r[3] == "read"; });
  REQUIRE(first_read != rows.end());
  CHECK((*first_read)[8] == "294913056");
  CHECK(tasks.size() == 4);
  // Every phase ran on the compute host: the storage host only serves the files.
  for (const auto& [task, phases] : tasks) {
    for (const auto& [phase, p] : phases) CHECK(p.host == "compute_host");
  }
}

TEST_CASE("the SimGrid platform examples load, and pcsim show prints their hosts, disks, links and routes", "[cli][inputs][simgrid]") {
  const fs::path dir = kInputs / "simgrid";
  {
    const auto shown = pcsim(fmt::format("show '{}'", (dir / "hosts_with_disks.xml").string()));
    INFO(shown.output);
    REQUIRE(shown.status == 0);
    for (const char* text : {"name = \"bob\"", "name = \"alice\"", "name = \"Disk1\"", "name = \"Disk2\"", "read_bw = \"100 MB/s\"",
                             "write_bw = \"40 MB/s\"", "capacity = \"500 GiB\"", "name = \"link1\"", "bandwidth = \"125 MB/s\"",
                             "latency = \"0.00015 s\"", "hosts = [ \"bob\", \"alice\" ]\nlinks = [ \"link1\" ]", "# memory = ?",
                             "prop 'content' is not modelled"}) {
      CHECK_THAT(shown.output, Catch::Contains(text));
    }
  }
  {
    const auto shown = pcsim(fmt::format("show '{}'", (dir / "small_platform.xml").string()));
    INFO(shown.output.substr(0, 4000));
    REQUIRE(shown.status == 0);
    for (const char* text : {"name = \"Tremblay\"", "name = \"Bourassa\"", "name = \"loopback\"", "sharing = \"fatpipe\"",
                             "hosts = [ \"Tremblay\", \"Fafard\" ]\nlinks = [ \"4\", \"3\", \"2\", \"0\", \"1\", \"8\" ]"}) {
      CHECK_THAT(shown.output, Catch::Contains(text));
    }
  }
  {
    const auto shown = pcsim(fmt::format("show '{}'", (dir / "cluster_backbone.xml").string()));
    INFO(shown.output.substr(0, 4000));
    REQUIRE(shown.status == 0);
    CHECK_THAT(shown.output, Catch::Contains("name = \"node-0.acme.org\""));
    CHECK_THAT(shown.output, Catch::Contains("name = \"node-99.acme.org\""));
    CHECK_THAT(shown.output, Catch::Contains("name = \"acme_backbone\""));
    std::size_t routes = 0;
    for (std::size_t at = shown.output.find("[[routes]]"); at != std::string::npos; at = shown.output.find("[[routes]]", at + 1)) ++routes;
    CHECK(routes == 100 * 99 / 2);
  }
}

TEST_CASE("every shipped SimGrid platform example is read, or refused for what pcsim does not model with its file and line",
          "[cli][inputs][simgrid]") {
  // What pcsim's reader does not model (README, "SimGrid platforms") is refused by name: none
  // of the thirteen asks for it. Each is shown, whole or summarised.
  const std::map<std::string, std::string> refused;
  std::size_t files = 0, read = 0;
  for (const auto& entry : fs::directory_iterator(kInputs / "simgrid")) {
    if (entry.path().extension() != ".xml") continue;
    ++files;
    const std::string name = entry.path().filename().string();
    const auto shown = pcsim(fmt::format("show '{}'", entry.path().string()));
    INFO(name << ": " << shown.output.substr(0, 2000));
    if (const auto it = refused.find(name); it != refused.end()) {
      CHECK(shown.status == 2);
      CHECK_THAT(shown.output, Catch::Contains("pcsim: " + entry.path().string() + it->second));
    } else {
      CHECK(shown.status == 0);
      CHECK_THAT(shown.output, Catch::Contains("[[hosts]]"));
      // More than 100 hosts (g5k.xml 1528, cluster_dragonfly.xml 120): a summary, said so.
      const bool large = name == "g5k.xml" || name == "cluster_dragonfly.xml";
      CHECK((shown.output.find(": a summary: ") != std::string::npos) == large);
      ++read;
    }
  }
  CHECK(files == 13);
  CHECK(read == files - refused.size());
}

namespace {

struct BadInput {
  const char* name;
  const char* file;  // "workflow.json" or "platform.xml": the one that is broken
  std::string text;
  std::vector<std::string> expected;  // in the message
};

const char* kGoodPlatform = R"(<?xml version="1.0"?>
<platform version="4.1">
  <zone id="z" routing="Full">
    <host id="h" speed="1Gf" core="4">
      <prop id="ram" value="16GB"/>
      <disk id="memory" read_bw="4000MBps" write_bw="4000MBps"><prop id="mount" value="/memory"/></disk>
      <disk id="d" read_bw="100MBps" write_bw="100MBps"><prop id="size" value="100GB"/></disk>
    </host>
  </zone>
</platform>
)";

std::string workflow(const std::string& tasks, const std::string& files) {
  return R"({"schemaVersion": "1.5", "name": "w", "workflow": {"specification": {"tasks": [)" + tasks + R"(], "files": [)" + files +
         R"(]}, "execution": {"makespanInSeconds": 1, "executedAt": "now", "tasks": [{"id": "a", "runtimeInSeconds": 1}, {"id": "b", "runtimeInSeconds": 1}]}}})";
}

const std::string kTaskA = R"({"name": "a", "id": "a", "parents": [], "children": ["b"], "inputFiles": ["in"], "outputFiles": ["mid"]})";
const std::string kTaskB = R"({"name": "b", "id": "b", "parents": ["a"], "children": [], "inputFiles": ["mid"], "outputFiles": ["out"]})";
const std::string kFiles = R"({"id": "in", "sizeInBytes": 1000}, {"id": "mid", "sizeInBytes": 1000}, {"id": "out", "sizeInBytes": 1000})";

std::string platform_with(const std::string& zone) {
  return R"(<?xml version="1.0"?>
<platform version="4.1">
  <zone id="z" routing=)" + zone + R"(>
    <host id="h" speed="1Gf"><prop id="ram" value="16GB"/>
      <disk id="memory" read_bw="4000MBps" write_bw="4000MBps"><prop id="mount" value="/memory"/></disk>
      <disk id="d" read_bw="100MBps" write_bw="100MBps"/></host>
    <host id="g" speed="1Gf"><prop id="ram" value="16GB"/>
      <disk id="memory" read_bw="4000MBps" write_bw="4000MBps"><prop id="mount" value="/memory"/></disk>
      <disk id="d" read_bw="100MBps" write_bw="100MBps"/></host>
    <link id="l" bandwidth="1GBps" latency="1us"/>
)";
}

}  // namespace

TEST_CASE("bad workflow and platform files are refused with exit 2, a message naming the file, line and element, and no output",
          "[cli][inputs][errors]") {
  const std::vector<BadInput> cases = {
      {"malformed JSON", "workflow.json", "{\"schemaVersion\": \"1.5\",\n  \"workflow\": {\n    \"specification\": [1, 2,, 3]\n}}",
       {"workflow.json:3:", "malformed JSON"}},
      {"malformed XML", "platform.xml", "<?xml version=\"1.0\"?>\n<platform version=\"4.1\">\n  <zone id=\"z\" routing=\"Full\">\n    <host id=\"h\"\n</platform>\n",
       {"platform.xml:", "malformed XML"}},
      {"a parent that does not exist", "workflow.json",
       workflow(kTaskA + ", " + R"({"name": "b", "id": "b", "parents": ["nobody"], "children": [], "inputFiles": ["mid"], "outputFiles": ["out"]})",
                kFiles),
       {"workflow.json", "parents", "nobody"}},
      {"a file that does not exist", "workflow.json",
       workflow(kTaskA + ", " + R"({"name": "b", "id": "b", "parents": ["a"], "children": [], "inputFiles": ["missing.dat"], "outputFiles": ["out"]})",
                kFiles),
       {"workflow.json", "inputFiles", "missing.dat"}},
      {"a missing size", "workflow.json", workflow(kTaskA + ", " + kTaskB, R"({"id": "in"}, {"id": "mid", "sizeInBytes": 1000}, {"id": "out", "sizeInBytes": 1000})"),
       {"workflow.json", "sizeInBytes"}},
      {"a negative size", "workflow.json",
       workflow(kTaskA + ", " + kTaskB, R"({"id": "in", "sizeInBytes": -5}, {"id": "mid", "sizeInBytes": 1000}, {"id": "out", "sizeInBytes": 1000})"),
       {"workflow.json", "sizeInBytes", "-5"}},
      {"a cycle", "workflow.json",
       workflow(R"({"name": "a", "id": "a", "parents": ["b"], "children": ["b"], "inputFiles": ["in"], "outputFiles": ["mid"]}, )" + kTaskB, kFiles),
       {"workflow.json", "cycle", "a", "b"}},
      {"an unknown host in a route", "platform.xml",
       platform_with("\"Full\"") + "    <route src=\"h\" dst=\"nowhere\"><link_ctn id=\"l\"/></route>\n  </zone>\n</platform>\n",
       {"platform.xml:11:", "route", "nowhere"}},
      {"a route between hosts with no link", "platform.xml", platform_with("\"Full\"") + "    <route src=\"h\" dst=\"g\"></route>\n  </zone>\n</platform>\n",
       {"platform.xml:11:", "route", "link"}},
      {"a routing pcsim refuses", "platform.xml", platform_with("\"Vivaldi\"") + "  </zone>\n</platform>\n",
       {"platform.xml:3:", "Vivaldi"}},
  };
  for (const BadInput& c : cases) {
    INFO(c.name);
    const fs::path dir = scratch(std::string("bad-input-") + c.name);
    std::ofstream(dir / "workflow.json") << workflow(kTaskA + ", " + kTaskB, kFiles);
    std::ofstream(dir / "platform.xml") << kGoodPlatform;
    std::ofstream(dir / c.file) << c.text;
    const auto run = pcsim(fmt::format("run workflow.json --platform platform.xml --out out"), dir);
    INFO(run.output);
    CHECK(run.status == 2);
    for (const std::string& text : c.expected) CHECK_THAT(run.output, Catch::Contains(text));
    CHECK_FALSE(fs::exists(dir / "out"));
  }
  // The control: the same files unbroken run.
  const fs::path dir = scratch("bad-input-control");
  std::ofstream(dir / "workflow.json") << workflow(kTaskA + ", " + kTaskB, kFiles);
  std::ofstream(dir / "platform.xml") << kGoodPlatform;
  const auto run = pcsim("run workflow.json --platform platform.xml --out out --quiet", dir);
  INFO(run.output);
  CHECK(run.status == 0);
  CHECK(fs::exists(dir / "out" / "timeline.csv"));
}

TEST_CASE("where a workflow's files live and its tasks run when no recorded machine is a host of the platform", "[cli][inputs]") {
  // helloworld ran on "ubuntu"; platforms/paper-cluster.toml has "node" and "storage".
  const auto placement = [](const std::string& options) {
    const auto shown = pcsim(fmt::format("show '{}' --platform '{}' {}", (kSource / "inputs" / "wfcommons" / "instances" / "helloworld-chain-5-chameleon.json").string(),
                                         (kSource / "platforms" / "paper-cluster.toml").string(), options));
    INFO(shown.output);
    REQUIRE(shown.status == 0);
    std::smatch files, hosts;
    REQUIRE(std::regex_search(shown.output, files, std::regex("name = \"chain_00000001_input.txt\"\nsize = \"[^\"]*\"\nhost = \"([a-z]+)\"")));
    REQUIRE(std::regex_search(shown.output, hosts, std::regex("\\[workflow\\]\nname = \"[^\"]*\"\n(host|hosts) = ([^\n]*)\n")));
    return std::pair{files[1].str(), hosts[2].str()};
  };
  // Everything on the first host, on its local disk.
  CHECK(placement("") == std::pair<std::string, std::string>{"node", "\"node\""});
  // A files host chosen: a storage server, the tasks on the other hosts.
  CHECK(placement("--files-host storage") == std::pair<std::string, std::string>{"storage", "\"node\""});
  // Hosts chosen: the files on the first of them.
  CHECK(placement("--hosts storage") == std::pair<std::string, std::string>{"storage", "\"storage\""});
  CHECK(placement("--hosts storage,node") == std::pair<std::string, std::string>{"storage", "[ \"storage\", \"node\" ]"});
}
