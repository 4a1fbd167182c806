// fio job files as scenarios ([fio] file = "JOB.fio", or pcsim run JOB.fio --platform P): each
// job and clone an application in fio's order, its files on the host's disk as large as the
// jobs' regions, its I/O an access of each file; what pcsim does not model yet refused, naming
// the job and the option. Expected values follow fio's rules (HOWTO, filesetup.c), not a run.
#include <pagecache/error.hpp>
#include <pagecache/outputs.hpp>
#include <pagecache/run.hpp>
#include <pagecache/scenario.hpp>
#include <pagecache/scenario_file.hpp>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <string>

namespace pagecache {
namespace {

namespace fs = std::filesystem;

// A folder with platform.toml (one host "node", disk "ssd") and the job file `name`.
struct JobFolder {
  fs::path dir;
  explicit JobFolder(const std::string& tag) : dir(fs::temp_directory_path() / ("pcsim-fio-scenario-" + tag)) {
    fs::remove_all(dir);
    fs::create_directories(dir);
    write("platform.toml", R"([[hosts]]
name = "node"
cores = 4
memory = "4 GB"
memory_read_bw = "10 GB/s"
memory_write_bw = "5 GB/s"
[[hosts.disks]]
name = "ssd"
read_bw = "500 MB/s"
write_bw = "400 MB/s"
request_latency = "100 us"
)");
  }
  ~JobFolder() { fs::remove_all(dir); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(dir / name) << text;
    return (dir / name).string();
  }
  Scenario load(const std::string& jobs, std::vector<std::pair<std::string, std::string>> overrides = {}) const {
    RunInputs in;
    in.workflow.platform = (dir / "platform.toml").string();
    in.overrides = std::move(overrides);
    return load_run_scenario(write("jobs.fio", jobs), in);
  }
  std::string error(const std::string& jobs) const {
    try {
      load(jobs);
    } catch (const ConfigError& e) {
      return e.what();
    }
    return "(no error)";
  }
};

const AccessSpec& access_of(const Scenario& s, std::size_t app) { return s.apps.at(app).tasks.at(0).accesses.at(0); }

}  // namespace

TEST_CASE("Each fio job and clone is an application, in fio's order, after what its stonewall waits for", "[fio][scenario]") {
  const JobFolder folder("order");
  const Scenario s = folder.load(R"([global]
size=64m
[w]
rw=write
[r]
stonewall
rw=read
numjobs=3
[last]
wait_for=w
)");
  REQUIRE(s.apps.size() == 6);
  // The files r's clones and last (rw's default, read) read are laid out first, by an
  // application the jobs that wait for nothing else wait for.
  CHECK(s.apps[0].name == "layout");
  REQUIRE(s.apps[0].tasks.size() == 4);
  CHECK(s.apps[0].tasks[0].accesses.at(0).file == "r.0.0");
  CHECK(s.apps[0].tasks[3].accesses.at(0).file == "last.0.0");
  // Clones keep their job's name: ".N" for clone N (fio numbers them 0, then 2, 1).
  CHECK(s.apps[1].name == "w");
  CHECK(s.apps[2].name == "r");
  CHECK(s.apps[3].name == "r.2");
  CHECK(s.apps[4].name == "r.1");
  CHECK(s.apps[5].name == "last");
  CHECK(s.apps[1].after == std::vector<std::string>{"layout"});
  for (std::size_t i = 2; i <= 4; ++i) CHECK(s.apps[i].after == std::vector<std::string>{"w"});
  // A job after a stonewalled one starts with it (fio's start loop passes the stonewall once
  // every job before it has ended), not after it: it too waits for w alone.
  CHECK(s.apps[5].after == std::vector<std::string>{"w"});
}

TEST_CASE("A fio job's files are the host's, as large as its region, and its I/O an access of each", "[fio][scenario]") {
  const JobFolder folder("files");
  const Scenario s = folder.load(R"([seq]
rw=read
bs=1m
size=64m
nrfiles=2
file_service_type=sequential
loops=3
[rand]
rw=randread
bs=4k
size=16m
offset=1m
norandommap
fadvise_hint=0
)");
  REQUIRE(s.files.size() == 3);
  // Generated names $jobname.$jobnum.$filenum; size / nrfiles each; offset + size for rand's.
  CHECK(s.files[0].name == "seq.0.0");
  CHECK(s.files[0].size == 32 * 1048576);
  CHECK(s.files[1].name == "seq.0.1");
  CHECK(s.files[2].name == "rand.0.0");
  CHECK(s.files[2].size == 17 * 1048576);
  for (const FileSpec& f : s.files) {
    CHECK(f.host == "node");
    CHECK(f.disk == "ssd");
    CHECK_FALSE(f.cached);  // laid out, synced and dropped from the cache before the jobs start
  }
  const std::vector<AccessSpec>& seq = s.apps[1].tasks[0].accesses;
  REQUIRE(seq.size() == 2);
  CHECK(seq[0].file == "seq.0.0");
  CHECK(seq[1].file == "seq.0.1");
  CHECK(seq[0].pattern == AccessPattern::Sequential);
  CHECK(seq[0].request == 1048576);
  CHECK(seq[0].length == 32 * 1048576);
  CHECK(seq[0].count == 32);
  CHECK(seq[0].repeat == 3);
  CHECK(seq[0].invalidate);  // fio's default invalidate=1, at each loop's open
  CHECK(seq[0].advice == AccessAdvice::Sequential);  // fadvise_hint=1 and a sequential rw
  const AccessSpec& rand = access_of(s, 2);
  CHECK(rand.pattern == AccessPattern::Random);
  CHECK(rand.offset == 1048576);
  CHECK(rand.length == 16 * 1048576);
  CHECK(rand.count == 4096);
  CHECK(rand.replacement);      // norandommap: independent draws
  CHECK_FALSE(rand.reshuffle);  // randrepeat=1: each loop the same offsets
  CHECK(rand.advice == AccessAdvice::Normal);  // fadvise_hint=0
}

TEST_CASE("fio lays out the files jobs read or overwrite before any job: written whole, fsynced, dropped", "[fio][scenario]") {
  const JobFolder folder("layout");
  const Scenario s = folder.load(R"([seq]
rw=read
bs=1m
size=64m
nrfiles=2
file_service_type=sequential
[rand]
rw=randread
bs=4k
size=16m
offset=1m
[w]
rw=write
size=8m
[o]
rw=randwrite
filename=over
size=8m
overwrite=1
[layout]
rw=read
filename=seq.0.0
size=32m
)");
  // The files in the jobs' order, each once (seq's first file, already as large as the last
  // job needs, is left as it is); w's file is only allocated (fallocate: no data written).
  REQUIRE(s.apps.size() == 6);
  const AppSpec& layout = s.apps[0];
  CHECK(layout.name == "layout#");  // a job has the name
  const std::vector<std::pair<std::string, std::int64_t>> expected{
      {"seq.0.0", 32 * 1048576}, {"seq.0.1", 32 * 1048576}, {"rand.0.0", 17 * 1048576}, {"over", 8 * 1048576}};
  REQUIRE(layout.tasks.size() == expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    const TaskSpec& t = layout.tasks[i];
    CHECK(t.fsync);  // create_fsync=1
    REQUIRE(t.accesses.size() == 1);
    const AccessSpec& a = t.accesses[0];
    CHECK(a.file == expected[i].first);
    CHECK(a.mode == AccessMode::Write);
    CHECK(a.pattern == AccessPattern::Sequential);
    CHECK(a.offset == 0);  // from byte 0, whatever the job's offset
    CHECK(a.length == expected[i].second);
    CHECK(a.request == (i == 2 ? 4096 : i == 3 ? 4096 : 1048576));  // the job's write requests
    CHECK(a.count * a.request == a.length);
    CHECK(a.drop_after);  // POSIX_FADV_DONTNEED after the fsync
  }
  for (std::size_t i = 1; i < s.apps.size(); ++i) CHECK(s.apps[i].after == std::vector<std::string>{"layout#"});
  // A file set up by an earlier job that only writes is not laid out again for a reader.
  CHECK(folder.load("[w]\nrw=write\nsize=8m\nfilename=f\n[r]\nstonewall\nrw=read\nsize=8m\nfilename=f\n").apps.size() == 2);
  // But one too small for the reader's region is.
  const Scenario grown = folder.load("[w]\nrw=write\nsize=8m\nfilename=f\n[r]\nstonewall\nrw=read\nsize=16m\nfilename=f\n");
  REQUIRE(grown.apps.size() == 3);
  CHECK(grown.apps[0].tasks.at(0).accesses.at(0).length == 16 * 1048576);
}

TEST_CASE("In a memory cgroup, fio's layout is the job's first task: fio runs whole in the group", "[fio][scenario]") {
  const JobFolder folder("layout-group");
  const Scenario s = folder.load("[r]\nrw=read\nbs=1m\nsize=64m\nloops=2\ninvalidate=0\n", {{"fio.memory_max", "\"32 MiB\""}});
  REQUIRE(s.apps.size() == 1);
  const AppSpec& r = s.apps[0];
  CHECK(r.memory_max == 32 * 1048576);
  CHECK(r.after.empty());
  REQUIRE(r.tasks.size() == 2);
  CHECK(r.tasks[0].name == "layout");
  CHECK(r.tasks[0].accesses.at(0).drop_after);
  CHECK(r.tasks[1].name == "io");
  // The group holds 32 MiB of the file: loop 2 reads it from disk again; fio.json counts the
  // job's reads only, not its layout's writes.
  RunOutputs outputs;
  RunOptions options;
  outputs.attach(options);
  const RunResult result = run_scenario(Scenario(s), options);
  std::vector<PhaseRow> reads;
  for (const PhaseRow& row : result.timeline) {
    if (result.task_name(row).rfind("io:", 0) == 0) reads.push_back(row);
  }
  REQUIRE(reads.size() == 2);
  CHECK(reads[1].disk_bytes == 64 * 1048576);
  const fs::path out = folder.dir / "out";
  outputs.write(out.string(), s, result);
  const nlohmann::json fio = nlohmann::json::parse(std::ifstream(out / "fio.json"));
  CHECK(fio["jobs"][0]["read"]["io_bytes"] == 128 * 1048576);
  CHECK(fio["jobs"][0]["write"]["io_bytes"] == 0);
}

TEST_CASE("fio's layout leaves the file on disk and not cached when the jobs start", "[fio][run]") {
  const JobFolder folder("layout-run");
  const RunResult result = run_scenario(folder.load("[r]\nrw=read\nbs=1m\nsize=64m\ninvalidate=0\n"));
  bool read = false;
  for (const PhaseRow& row : result.timeline) {
    if (result.names[row.app] != "r" || row.phase != PhaseKind::Read || row.bytes == 0) continue;
    read = true;
    CHECK(row.disk_bytes == 64 * 1048576);  // dropped by the layout even without the job's invalidate
    CHECK(row.cache_bytes == 0);
    CHECK(row.start > 0.0);  // after the layout's writes and fsync
  }
  CHECK(read);
}

TEST_CASE("fio's end_fsync, unlink, io_size and filename map onto the task", "[fio][scenario]") {
  const JobFolder folder("task");
  const Scenario s = folder.load(R"([w]
rw=randwrite
filename=data
size=8m
io_size=32m
end_fsync=1
unlink=1
)");
  REQUIRE(s.files.size() == 1);
  CHECK(s.files[0].name == "data");
  const TaskSpec& t = s.apps[0].tasks[0];
  CHECK(t.fsync);
  CHECK_FALSE(t.direct_io);
  CHECK(folder.load("[d]\nsize=1m\ndirect=1\n").apps[1].tasks[0].direct_io);  // O_DIRECT, request by request (after the layout)
  CHECK(t.deletes == std::vector<std::string>{"data"});
  CHECK(t.accesses[0].mode == AccessMode::Write);
  CHECK(t.accesses[0].count == 8192);  // io_size / bs: four passes over the 8 MiB region
}

TEST_CASE("What pcsim does not model yet is refused, naming the job file, line, job and option", "[fio][scenario]") {
  const JobFolder folder("refused");
  CHECK_THAT(folder.error("[a]\nsize=1m\n\n[mix]\nrw=randrw\nsize=1m\n"),
             Catch::Contains("jobs.fio:4: job 'mix': rw: mixed reads and writes are not modelled yet"));
  CHECK_THAT(folder.error("[f]\nrw=write\nsize=1m\nfsync=4\n"), Catch::Contains("job 'f': fsync:"));
  CHECK_THAT(folder.error("[n]\nsize=1m\nnrfiles=4\n"), Catch::Contains("job 'n': nrfiles:"));
  CHECK_THAT(folder.error("[t]\nsize=1m\nruntime=10\ntime_based\n"), Catch::Contains("job 't': time_based:"));
  CHECK_THAT(folder.error("[nosize]\nrw=read\n"), Catch::Contains("job 'nosize': size: needed"));
}

TEST_CASE("pcsim show of a fio job file prints a scenario that reads back the same", "[fio][scenario]") {
  const JobFolder folder("show");
  const Scenario s = folder.load("[w]\nrw=randwrite\nsize=8m\nend_fsync=1\n[r]\nstonewall\nrw=read\nfilename=w.0.0\nsize=8m\ndirect=1\nruntime=5\n");
  const std::string shown = to_toml(s);
  const Scenario back = parse_scenario(shown, "shown.toml");
  CHECK(to_toml(back).substr(to_toml(back).find('\n')) == shown.substr(shown.find('\n')));
  CHECK(back.apps.size() == 2);
  CHECK(back.apps[1].after == std::vector<std::string>{"w"});
  CHECK(back.apps[1].tasks[0].accesses[0].runtime == 5.0);
}

TEST_CASE("A fio job file needs a platform, and is the whole workload", "[fio][scenario]") {
  const JobFolder folder("platform");
  const std::string jobs = folder.write("jobs.fio", "[a]\nsize=1m\n");
  CHECK_THROWS_WITH(load_run_scenario(jobs, RunInputs{}), Catch::Contains("a fio job file runs on a platform: add --platform"));
  const std::string both = folder.write("both.toml", "platform = \"platform.toml\"\n[fio]\nfile = \"jobs.fio\"\n[[apps]]\nname = \"x\"\n");
  CHECK_THROWS_WITH(load_scenario(both), Catch::Contains("[apps] cannot come with it"));
  CHECK_THROWS_WITH(folder.load("[a]\nsize=1m\n", {{"fio.disk", "\"nvme\""}}), Catch::Contains("no disk named 'nvme'"));
  // A fio run in a memory cgroup: one job's application is its group; several are refused.
  CHECK(folder.load("[a]\nsize=1m\n", {{"fio.memory_max", "\"1 GB\""}}).apps[0].memory_max == 1'000'000'000);
  CHECK_THROWS_WITH(folder.load("[a]\nsize=1m\nnumjobs=2\n", {{"fio.memory_max", "\"1 GB\""}}),
                    Catch::Contains("2 jobs in one memory cgroup are not modelled yet"));
}

TEST_CASE("A job reading what an earlier one wrote reads it from the disk, as fio's invalidate drops it", "[fio][run]") {
  const JobFolder folder("run");
  const std::string jobs = R"([w]
rw=write
bs=1m
size=64m
filename=data
end_fsync=1
[r]
stonewall
rw=read
bs=1m
size=64m
filename=data
)";
  const auto read_row = [](const RunResult& result) {
    for (const PhaseRow& row : result.timeline) {
      if (result.names[row.app] == "r" && row.phase == PhaseKind::Read && row.bytes > 0) return row;
    }
    FAIL("no read row of job r");
    return PhaseRow{};
  };
  const PhaseRow dropped = read_row(run_scenario(folder.load(jobs)));
  CHECK(dropped.disk_bytes == 64 * 1048576);
  CHECK(dropped.cache_bytes == 0);
  const PhaseRow kept = read_row(run_scenario(folder.load(jobs + "invalidate=0\n")));
  CHECK(kept.cache_bytes == 64 * 1048576);
  CHECK(kept.disk_bytes == 0);
}

TEST_CASE("fio.json reports each job as fio names it: bytes, requests, runtime and rates", "[fio][run]") {
  const JobFolder folder("json");
  Scenario s = folder.load(R"([global]
size=32m
[w]
rw=write
bs=64k
[r]
stonewall
rw=randread
bs=4k
numjobs=2
)");
  RunOutputs outputs;
  RunOptions options;
  outputs.attach(options);
  const Scenario named = s;
  const RunResult result = run_scenario(std::move(s), options);
  const fs::path out = folder.dir / "out";
  outputs.write(out.string(), named, result);
  const nlohmann::json fio = nlohmann::json::parse(std::ifstream(out / "fio.json"));
  CHECK(fio["global options"]["size"] == "32m");
  const nlohmann::json& jobs = fio["jobs"];
  REQUIRE(jobs.size() == 3);
  CHECK(jobs[0]["jobname"] == "w");
  CHECK(jobs[1]["jobname"] == "r");
  CHECK(jobs[2]["jobname"] == "r");  // a clone is reported under its job's name
  CHECK(jobs[2]["pcsim_application"] == "r.1");
  CHECK(jobs[0]["groupid"] == 0);
  CHECK(jobs[1]["groupid"] == 1);
  CHECK(jobs[2]["groupid"] == 1);
  CHECK(jobs[1]["job options"]["rw"] == "randread");
  CHECK(jobs[0]["write"]["io_bytes"] == 32 * 1048576);
  CHECK(jobs[0]["write"]["total_ios"] == 512);  // 32 MiB of 64 KiB
  CHECK(jobs[0]["read"]["io_bytes"] == 0);
  CHECK(jobs[1]["read"]["total_ios"] == 8192);  // each 4 KiB block once (fio's random map)
  // runtime: the job's rows' span, in ms; bw_bytes and iops over the same seconds.
  for (std::size_t j = 0; j < 3; ++j) {
    const char* dir = j == 0 ? "write" : "read";
    double start = 1e300;
    double end = 0.0;
    for (const PhaseRow& row : result.timeline) {
      if (result.app_name(row) != jobs[j]["pcsim_application"].get<std::string>() || row.bytes == 0) continue;
      start = std::min(start, row.start);
      end = std::max(end, row.end);
    }
    const double seconds = end - start;
    CHECK(jobs[j][dir]["runtime"] == std::llround(seconds * 1000.0));
    CHECK(jobs[j][dir]["bw_bytes"] == std::llround(32.0 * 1048576 / seconds));
    CHECK(jobs[j][dir]["bw"] == std::llround(32.0 * 1048576 / seconds) / 1024);
    CHECK(jobs[j][dir]["iops"].get<double>() == Approx(jobs[j][dir]["total_ios"].get<double>() / seconds));
  }
}


TEST_CASE("A fio job file's files and tasks are held to the run's limits on the declared counts", "[fio][scenario][limits]") {
  const JobFolder folder("limits");
  const auto error = [&](const std::string& jobs, const ScenarioLimits& limits) -> std::string {
    RunInputs in;
    in.workflow.platform = (folder.dir / "platform.toml").string();
    in.limits = limits;
    try {
      load_run_scenario(folder.write("jobs.fio", jobs), in);
    } catch (const ConfigError& e) {
      return e.what();
    }
    return "(no error)";
  };
  ScenarioLimits limits;
  limits.max_files = 20;
  limits.max_tasks = 10;
  // Files: nrfiles alone, then over clones (numjobs), then filename= entries.
  CHECK_THAT(error("[j]\nrw=write\nsize=1m\nnrfiles=21\nfile_service_type=sequential\n", limits),
             Catch::Contains("jobs.fio:4: option 'nrfiles=21': more than the 20 files a run may have without --force"));
  CHECK_THAT(error("[j]\nrw=write\nsize=1m\nnrfiles=5\nnumjobs=5\nfile_service_type=sequential\n", limits),
             Catch::Contains("jobs.fio:1: job 'j': the jobs would name 25 files, more than the 20 a run may have without --force"));
  CHECK_THAT(error("[j]\nrw=write\nsize=1m\nfilename=a:b:c\n[k]\nrw=write\nsize=1m\nnumjobs=9\nnrfiles=2\nfile_service_type=sequential\n", limits),
             Catch::Contains("job 'k': the jobs would name 21 files"));
  // Tasks: a job each, and fio's layout of each file a reading job reads: 12 files to lay out.
  CHECK_THAT(error("[j]\nrw=read\nsize=12m\nnrfiles=12\nfile_service_type=sequential\n", limits),
             Catch::Contains("job 'j': nrfiles: the jobs and fio's layout of their files (a task per file laid out) would be 13 tasks, more than the 10"));
  CHECK_THAT(error("[j]\nrw=read\nsize=1m\nnumjobs=11\n", limits), Catch::Contains("numjobs=11"));
  // Within the limits: four files laid out and a job, five tasks (and 23 timeline rows of 30).
  CHECK(error("[j]\nrw=read\nsize=4m\nnrfiles=4\nfile_service_type=sequential\n", limits) == "(no error)");
}

}  // namespace pagecache
