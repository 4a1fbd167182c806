// pcsim validate --here --fio, run as a user runs it, with the real fio (scripts/install-deps
// installs it): a tiny job file run twice in a scratch folder pcsim makes and removes, its
// reports kept and scored, the scores equal to what fio's own reports say, and --from scoring
// the kept folder again; a job file pcsim refuses, and a missing --dir, refused before fio runs;
// --memory-max: fio in a memory cgroup of that limit (root only: skipped otherwise), pcsim under it.
#include "support/files.hpp"
#include "support/pcsim_cli.hpp"

#include <catch2/catch.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using nlohmann::json;
using pagecache::testing::names;
using pagecache::testing::pcsim;
using pagecache::testing::scratch;
using pagecache::testing::slurp;

namespace {

// 8 MiB written and synced, then (after a stonewall) read: a run of well under a second.
constexpr const char* kTinyJob = R"([global]
bs=1m
size=8m

[write]
rw=write
end_fsync=1

[read]
stonewall
rw=read
)";

const std::string kDevPlatform = std::string(PCSIM_SOURCE_DIR) + "/platforms/dev-vm-2026-12-05.toml";

fs::path write_job(const fs::path& dir, const std::string& name, const std::string& text) {
  std::ofstream(dir / name) << text;
  return dir / name;
}

// A scratch root holding the job file `name`, the --dir `run/` and room for the --out `out/`.
struct FioCase {
  fs::path root, job, dir, out;
  FioCase(const std::string& test, const std::string& name, const std::string& text)
      : root(scratch(test)), job(write_job(root, name, text)), dir(root / "run"), out(root / "out") {
    fs::create_directories(dir);
  }
  ~FioCase() { fs::remove_all(root); }
  // pcsim validate --here --fio on the development machine's platform.
  pagecache::testing::Outcome run(const std::string& more = "") const {
    return pcsim(fmt::format("validate --here --fio '{}' --dir '{}' --platform '{}' --out '{}' {}", job.string(), dir.string(), kDevPlatform,
                             out.string(), more));
  }
};

double median_of(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.size() % 2 == 1 ? v[v.size() / 2] : (v[v.size() / 2 - 1] + v[v.size() / 2]) / 2.0;
}

}  // namespace

TEST_CASE("validate --here --fio runs the real fio in a folder of its own, keeps its reports and scores pcsim against them", "[fio][here]") {
  const FioCase c("validate-fio", "tiny.fio", kTinyJob);
  const fs::path& dir = c.dir;
  const fs::path& out = c.out;
  const auto run = c.run("--repeat 2");
  INFO(run.output);
  REQUIRE(run.status == 0);
  CHECK(run.output.find("tiny.fio") != std::string::npos);
  CHECK(run.output.find(" write ") != std::string::npos);
  CHECK(run.output.find(" read ") != std::string::npos);
  CHECK(names(dir).empty());  // the scratch folder and fio's files are gone

  // fio really ran: its reports hold its own fields for both jobs, in the job file's order.
  std::vector<json> reports;
  for (int rep = 1; rep <= 2; ++rep) {
    const json r = json::parse(slurp(out / fmt::format("fio-tiny-{}.json", rep)));
    CHECK(r.at("fio version").get<std::string>().rfind("fio-", 0) == 0);
    REQUIRE(r.at("jobs").size() == 2);
    CHECK(r["jobs"][0]["jobname"] == "write");
    CHECK(r["jobs"][0]["write"]["io_bytes"] == 8 << 20);
    CHECK(r["jobs"][1]["jobname"] == "read");
    CHECK(r["jobs"][1]["read"]["io_bytes"] == 8 << 20);
    reports.push_back(r);
  }
  CHECK(slurp(out / "tiny.fio") == kTinyJob);
  CHECK(fs::exists(out / "platform.toml"));

  // The scores' measured figures are the reports' bw_bytes, and their median.
  const json scores = json::parse(slurp(out / "fio-scores.json"));
  REQUIRE(scores.at("scores").size() == 2);
  const std::vector<std::pair<int, std::string>> expected{{0, "write"}, {1, "read"}};
  for (std::size_t i = 0; i < expected.size(); ++i) {
    const auto& [j, direction] = expected[i];
    const json& s = scores["scores"][i];
    CHECK(s["job_file"] == "tiny.fio");
    CHECK(s["job"] == direction);
    CHECK(s["direction"] == direction);
    std::vector<double> measured;
    for (const json& r : reports) measured.push_back(r["jobs"][j][direction]["bw_bytes"].get<double>());
    CHECK(s["measured_bytes_per_second"].get<std::vector<double>>() == measured);
    CHECK(s["median_bytes_per_second"].get<double>() == Approx(median_of(measured)));
    CHECK(s["pcsim_bytes_per_second"].get<double>() > 0.0);
    const double error = s["pcsim_bytes_per_second"].get<double>() / median_of(measured) - 1.0;
    CHECK(s["error"].get<double>() == Approx(error));
    const double spread = s["spread"].get<double>();
    CHECK(s["verdict"] == (std::abs(error) <= std::max(0.15, spread) ? "within" : "off"));
  }

  // --from scores the kept folder again, without fio: the same table.
  const auto again = pcsim(fmt::format("validate --from '{}'", out.string()));
  INFO(again.output);
  CHECK(again.status == 0);
  CHECK(again.output == slurp(out / "report.txt"));
  CHECK(run.output.find(again.output) != std::string::npos);  // after any warning on stderr

  // A kept report broken: --from names it.
  std::ofstream(out / "fio-tiny-2.json") << "{\"jobs\": [";
  const auto broken = pcsim(fmt::format("validate --from '{}'", out.string()));
  CHECK(broken.status == 2);
  CHECK(broken.output.find("fio-tiny-2.json") != std::string::npos);
}

TEST_CASE("validate --here --fio refuses a job file pcsim refuses before fio runs", "[fio][here]") {
  const FioCase c("validate-fio-refused", "mixed.fio", "[mixed]\nrw=randrw\nsize=8m\n");
  const auto run = c.run("--repeat 1");
  INFO(run.output);
  CHECK(run.status == 2);
  CHECK(run.output.find("mixed.fio:1: job 'mixed': rw: mixed reads and writes are not modelled") != std::string::npos);
  CHECK(names(c.dir).empty());
  CHECK(!fs::exists(c.out));
}

TEST_CASE("validate --here --fio refuses a --dir that does not exist, naming it", "[fio][here]") {
  const FioCase c("validate-fio-nodir", "tiny.fio", kTinyJob);
  fs::remove(c.dir);
  const auto run = c.run();
  INFO(run.output);
  CHECK(run.status == 2);
  CHECK(run.output.find("--dir '" + c.dir.string() + "': not a folder") != std::string::npos);
  CHECK(!fs::exists(c.out));
}

TEST_CASE("validate --here --fio refuses a job file whose files lie outside the folder fio runs in", "[fio][here]") {
  const fs::path elsewhere = scratch("validate-fio-outside") / "elsewhere";
  const FioCase c("validate-fio-outside", "outside.fio", fmt::format("[r]\nrw=read\nsize=8m\nfilename={}/x\n", elsewhere.string()));
  const auto run = c.run();
  INFO(run.output);
  CHECK(run.status == 2);
  CHECK(run.output.find("outside.fio:1: job 'r': its file '" + elsewhere.string() + "/x' is outside") != std::string::npos);
  CHECK(!fs::exists(elsewhere));
  CHECK(names(c.dir).empty());
}

TEST_CASE("validate --here --fio stops when fio fails, quoting its stderr, and leaves --dir as it was", "[fio][here]") {
  // pcsim takes directory=sub; fio refuses it, as sub does not exist where it runs.
  const FioCase c("validate-fio-fails", "sub.fio", "[r]\nrw=read\nsize=8m\ndirectory=sub\n");
  const auto run = c.run();
  INFO(run.output);
  CHECK(run.status == 1);
  CHECK(run.output.find("sub.fio failed (exit status 1)") != std::string::npos);
  CHECK(run.output.find("fio: sub is not a directory") != std::string::npos);
  CHECK(names(c.dir).empty());
  CHECK(!fs::exists(c.out / "fio-runs.csv"));
}

TEST_CASE("validate's --fio and --fio-timeout are refused without --here, not ignored", "[fio][here]") {
  const auto run = pcsim("validate --fio x.fio --fio-timeout 10");
  CHECK(run.status == 2);
  CHECK(run.output.find("pcsim: validate: --fio, --fio-timeout are options of --here") != std::string::npos);
}

namespace {

// The pcsim-fio-* memory cgroups below this process's (pcsim's) groups, v1 and v2, whose
// maker has exited: one that a run left behind. Those of a live process (a concurrent test's) are
// not counted.
std::vector<std::string> abandoned_fio_cgroups() {
  std::vector<fs::path> parents;
  std::ifstream self("/proc/self/cgroup");
  for (std::string line; std::getline(self, line);) {
    const auto colon = line.find(':');
    if (line.compare(colon, 8, ":memory:") == 0) parents.push_back(fs::path("/sys/fs/cgroup/memory") / line.substr(colon + 9));
    if (line.compare(colon, 2, "::") == 0) {
      parents.push_back(fs::path("/sys/fs/cgroup/unified") / line.substr(colon + 3));
      parents.push_back(fs::path("/sys/fs/cgroup") / line.substr(colon + 3));
    }
  }
  std::vector<std::string> left;
  for (const fs::path& parent : parents) {
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(parent, ec)) {
      const std::string name = entry.path().filename().string();
      if (name.rfind("pcsim-fio-", 0) != 0) continue;
      const std::string pid = name.substr(10, name.find('-', 10) - 10);
      if (!fs::exists("/proc/" + pid)) left.push_back(entry.path().string());
    }
  }
  return left;
}

// Twice the limit written: pcsim simulates it differently in 64 MiB than on the whole machine.
constexpr const char* kWriteJob = "[write]\nrw=write\nbs=1m\nsize=128m\n";

}  // namespace

TEST_CASE("validate --here --fio --memory-max runs fio in a memory cgroup of that limit, simulates under it and removes the cgroup", "[fio][here]") {
  const FioCase c("validate-fio-memory-max", "write.fio", kWriteJob);
  const std::vector<std::string> before = abandoned_fio_cgroups();
  const auto run = c.run("--quick --memory-max '64 MiB'");
  INFO(run.output);
  if (run.status == 1 && run.output.find("needs a memory cgroup this user may make") != std::string::npos) {
    WARN("skipped: this user may not make a memory cgroup (CI runs as root): " << run.output);
    return;
  }
  REQUIRE(run.status == 0);
  CHECK(abandoned_fio_cgroups() == before);  // each run's cgroup removed after it
  CHECK(names(c.dir).empty());

  const json report = json::parse(slurp(c.out / "fio-write-1.json"));
  CHECK(report.at("jobs").at(0).at("write").at("io_bytes") == 128 << 20);

  // The manifest records the limit and fio's peak use under it: at most the limit.
  const std::string manifest = slurp(c.out / "fio-runs.csv");
  INFO(manifest);
  CHECK(manifest.rfind("job_file,repetition,json_file,memory_max,peak_memory\nwrite.fio,1,fio-write-1.json,67108864,", 0) == 0);
  const std::string peak = manifest.substr(manifest.rfind(',') + 1);
  CHECK(std::stoll(peak) > 0);
  CHECK(std::stoll(peak) <= 64 << 20);

  const json scores = json::parse(slurp(c.out / "fio-scores.json"));
  REQUIRE(scores.at("scores").size() == 1);
  CHECK(scores["scores"][0]["pcsim_bytes_per_second"].get<double>() > 0.0);

  // --from rescored under the recorded limit: the same table.
  const auto again = pcsim(fmt::format("validate --from '{}'", c.out.string()));
  CHECK(again.status == 0);
  CHECK(again.output == slurp(c.out / "report.txt"));

  // An older manifest, without the columns, reads as a run without a limit: pcsim's figure
  // is the whole machine's, not the cgroup's.
  std::ofstream(c.out / "fio-runs.csv") << "job_file,repetition,json_file\nwrite.fio,1,fio-write-1.json\n";
  const auto old = pcsim(fmt::format("validate --from '{}'", c.out.string()));
  CHECK(old.status == 0);
  CHECK(old.output.find("write.fio") != std::string::npos);
  CHECK(old.output != again.output);
}

TEST_CASE("validate --here --fio --memory-max refuses a job file of several jobs before fio runs", "[fio][here]") {
  const FioCase c("validate-fio-memory-max-two", "two.fio", kTinyJob);
  const auto run = c.run("--memory-max '64 MiB'");
  INFO(run.output);
  CHECK(run.status == 2);
  CHECK(run.output.find("two.fio: --memory-max: 2 jobs (numjobs clones count) in one memory cgroup are not modelled yet") != std::string::npos);
  CHECK(names(c.dir).empty());
  CHECK(!fs::exists(c.out));
}

TEST_CASE("validate's --memory-max is refused without --here --fio, not ignored", "[fio][here]") {
  const auto from = pcsim("validate --from x --memory-max '64 MiB'");
  CHECK(from.status == 2);
  CHECK(from.output.find("pcsim: validate: --memory-max is an option of --here") != std::string::npos);
  const auto here = pcsim("validate --here --dir . --memory-max '64 MiB'");
  CHECK(here.status == 2);
  CHECK(here.output.find("pcsim: validate: --memory-max is an option of --here --fio") != std::string::npos);
  const auto bad = pcsim("validate --here --fio x.fio --dir . --memory-max '64 Mfoo'");
  CHECK(bad.status == 2);
  CHECK(bad.output.find("--memory-max: '64 Mfoo': unknown size unit") != std::string::npos);
}
