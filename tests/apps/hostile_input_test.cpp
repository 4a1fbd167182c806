// pcsim given what a tester would give it (issue 15): values that overflow, durations and
// bandwidths that would run for ever, inputs that are not files, misspellings. Each must end
// within 5 s and 200 MB, with exit status 2 and a message naming the file, line and key (or
// the --set option), or, where the value is deliberate, run quickly to the end.

#include "support/bounded_cli.hpp"
#include "support/files.hpp"
#include "support/pcsim_cli.hpp"

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <sys/stat.h>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;
using pagecache::testing::bounded_pcsim;
using pagecache::testing::ChildResult;
using pagecache::testing::refused;
using pagecache::testing::run_child;
using pagecache::testing::scratch;

namespace {

// Two tasks of one pipeline, 1 GB files, a 100 MB/s disk of 10 GB: two seconds of work.
const std::string kBase = std::string(pagecache::testing::kPlatform) + R"([pipelines]
file_size = "1 GB"
tasks = 2
cpu_time = "1 s"
)";

// pcsim with `args`, checked to have ended within 5 s and 200 MB.
ChildResult pcsim(std::vector<std::string> args, const std::string& cwd = {}) { return bounded_pcsim(std::move(args), 5.0, cwd); }

// The base scenario with `line` replaced by `with` (or appended when `line` is empty), run.
ChildResult run_edited(const std::string& name, const std::string& line, const std::string& with, std::vector<std::string> extra = {}) {
  std::string text = kBase;
  if (line.empty()) {
    text += with + "\n";
  } else {
    REQUIRE(text.find(line) != std::string::npos);
    text.replace(text.find(line), line.size(), with);
  }
  const fs::path dir = scratch(name);
  std::ofstream(dir / "s.toml") << text;
  std::vector<std::string> args{"run", (dir / "s.toml").string(), "--out", (dir / "out").string(), "--quiet"};
  args.insert(args.end(), extra.begin(), extra.end());
  return pcsim(args);
}

}  // namespace

TEST_CASE("counts that overflow or would fill the memory are refused before anything is built", "[cli][hostile]") {
  refused(run_edited("tasks", "tasks = 2", "tasks = 9223372036854775807"), {"s.toml:14:9: key 'pipelines.tasks'", "tasks"});
  refused(run_edited("count", "", "count = 1000000000"), {"s.toml:16:9: key 'pipelines.count'", "more than the 1000000"});
  // --force lifts the limit on what a run may have, not on what pcsim can represent.
  refused(run_edited("count_forced", "", "count = 1000000000", {"--force"}), {"key 'pipelines.count'", "more than the 500000000"});
  refused(run_edited("cores", "name = \"h\"", "name = \"h\"\ncores = 4294967297"), {"key 'hosts[0].cores'", "between 1 and 1000000"});
}

TEST_CASE("memory running out is exit status 3 with a message, not a crash", "[cli][hostile]") {
#if defined(__SANITIZE_ADDRESS__)
  // AddressSanitizer reserves terabytes of address space up front: a limit on it stops the
  // sanitizer, not the allocation. The release build runs this.
  SUCCEED("not under AddressSanitizer");
#else
  // 10^7 pipelines, allowed with --force, in 1 GB of address space.
  const fs::path dir = scratch("oom");
  std::ofstream(dir / "s.toml") << kBase << "count = 10000000\n";
  const ChildResult r =
      run_child({PCSIM_BINARY, "show", (dir / "s.toml").string(), "--force"}, 60.0, {}, rlim_t{1} << 30);
  INFO(r.output);
  CHECK(r.status == 3);
  CHECK_THAT(r.output, Catch::Contains("pcsim: out of memory"));
#endif
}

TEST_CASE("sizes that do not fit 64 bits are refused with the key, never cast", "[cli][hostile]") {
  refused(run_edited("inf", "file_size = \"1 GB\"", "file_size = inf"), {"s.toml:13:13: key 'pipelines.file_size'", "too large"});
  refused(run_edited("1e30", "file_size = \"1 GB\"", "file_size = 1e30"), {"key 'pipelines.file_size'", "too large"});
  refused(run_edited("exa", "file_size = \"1 GB\"", "file_size = \"9 EB\""), {"key 'pipelines.file_size'", "too large"});
  refused(run_edited("nan", "file_size = \"1 GB\"", "file_size = nan"), {"key 'pipelines.file_size'", "nan"});
  refused(run_edited("chunk", "", "chunk_size = inf"), {"key 'pipelines.chunk_size'", "too large"});
  refused(run_edited("chunk0", "", "chunk_size = 0.4"), {"key 'pipelines.chunk_size'", "must be > 0"});
}

TEST_CASE("durations and bandwidths that would run for ever are refused with the key", "[cli][hostile]") {
  refused(run_edited("cpu", "cpu_time = \"1 s\"", "cpu_time = \"1e300 s\""), {"s.toml:15:12: key 'pipelines.cpu_time'", "too long"});
  refused(run_edited("cpu_inf", "cpu_time = \"1 s\"", "cpu_time = inf"), {"key 'pipelines.cpu_time'", "too long"});
  refused(run_edited("tiny_bw", "read_bw = \"100 MB/s\"", "read_bw = 1e-300"), {"s.toml:9:11: key 'hosts[0].disks[0].read_bw'", "at least 1 B/s"});
  refused(run_edited("milli_bw", "read_bw = \"100 MB/s\"", "read_bw = \"0.001 B/s\""), {"key 'hosts[0].disks[0].read_bw'", "at least 1 B/s"});
  // A bare number is bytes per second: 465 is far more often "465 MB/s" without its unit.
  refused(run_edited("bare_bw", "read_bw = \"100 MB/s\"", "read_bw = 465"), {"key 'hosts[0].disks[0].read_bw'", "\"465 MB/s\""});
  // A year of simulated time per task is more than a run may take without --force.
  refused(run_edited("slow_disk", "read_bw = \"100 MB/s\"", "read_bw = \"1 B/s\""),
          {"key 'hosts[0].disks[0].read_bw'", "simulated time", "without --force"});
  refused(run_edited("flusher", "[pipelines]", "[hosts.page_cache]\nwriteback_interval = \"1 ns\"\n[pipelines]"),
          {"key 'hosts[0].page_cache.writeback_interval'", "wake"});
  refused(run_edited("chunks", "", "chunk_size = 1"), {"key 'pipelines.chunk_size'", "chunk operations"});
}

TEST_CASE("deliberate long runs end quickly: the run's events follow its work, not its simulated length", "[cli][hostile]") {
  // 465 B/s said explicitly: 2 GB read at 465 B/s is 50 simulated days.
  const ChildResult slow = run_edited("explicit_bw", "read_bw = \"100 MB/s\"", "read_bw = \"465 B/s\"");
  CHECK(slow.status == 0);
  const ChildResult fine = run_edited("fine_sampling", "profile = \"paper\"", "profile = \"paper\"\nmemory_sample_interval = \"1 ns\"");
  CHECK(fine.status == 0);
  const ChildResult compute = run_edited("long_compute", "cpu_time = \"1 s\"", "cpu_time = \"5e7 s\"");
  CHECK(compute.status == 0);
}

TEST_CASE("what is not a regular file of a sane size is refused at once", "[cli][hostile]") {
  const fs::path dir = scratch("files");
  refused(pcsim({"run", "/dev/zero", "--out", (dir / "out").string()}), {"/dev/zero: not a regular file"});
  REQUIRE(::mkfifo((dir / "fifo").c_str(), 0600) == 0);
  refused(pcsim({"run", (dir / "fifo").string(), "--out", (dir / "out").string()}), {"fifo: not a regular file"});
  refused(pcsim({"run", dir.string(), "--out", (dir / "out").string()}), {"is a folder"});
  std::ofstream(dir / "huge.toml").close();
  fs::resize_file(dir / "huge.toml", 65 << 20);  // sparse: nothing written
  refused(pcsim({"run", (dir / "huge.toml").string(), "--out", (dir / "out").string()}), {"huge.toml:", "too large", "64 MiB"});
  // A platform file is read the same way.
  refused(run_edited("platform", "profile = \"paper\"", "profile = \"paper\"\nplatform = \"/dev/zero\""), {"key 'platform'", "not a regular file"});
  CHECK_FALSE(fs::exists(dir / "out"));
}

TEST_CASE("checks across keys: the files on a disk together, the background ratio under the dirty ratio", "[cli][hostile]") {
  // 20 pipelines of 2 tasks: 60 files of 1 GB, 20 of them inputs, on a 10 GB disk.
  refused(run_edited("disk_total", "", "count = 20"), {"s.toml:11:12: key 'hosts[0].disks[0].capacity'", "60 GB when the run ends", "10 GB"});
  refused(run_edited("background", "[pipelines]", "[hosts.page_cache]\ndirty_background_ratio = 0.5\n[pipelines]"),
          {"key 'hosts[0].page_cache.dirty_background_ratio'", "must not be above dirty_ratio (0.4, the profile's default)"});
  refused(run_edited("ratio", "[pipelines]", "[hosts.page_cache]\ndirty_ratio = 0.05\n[pipelines]"),
          {"key 'hosts[0].page_cache.dirty_ratio'", "dirty_background_ratio (0.1, the profile's default)"});
}

TEST_CASE("a memory limit is a positive size, and pcsim show prints an application's", "[cli][hostile]") {
  refused(run_edited("memory_max", "[pipelines]", "[pipelines]\nmemory_max = \"0 GB\""),
          {"key 'pipelines.memory_max'", "must be > 0"});
  const fs::path dir = scratch("memory_max_shown");
  std::string text = kBase;
  text.replace(text.find("[pipelines]"), 11, "[pipelines]\nmemory_max = \"3 GB\"");
  std::ofstream(dir / "s.toml") << text;
  const ChildResult shown = pcsim({"show", (dir / "s.toml").string()});
  REQUIRE(shown.status == 0);
  CHECK_THAT(shown.output, Catch::Contains("memory_max = \"3 GB\""));
}

TEST_CASE("a disk's aggregate bandwidth is not below one stream's, and pcsim show prints it", "[cli][hostile]") {
  refused(run_edited("aggregate", "capacity = \"10 GB\"", "capacity = \"10 GB\"\naggregate_read_bw = \"1 MB/s\""),
          {"key 'hosts[0].disks[0].aggregate_read_bw'", "must not be below one stream's bandwidth"});
  const fs::path dir = scratch("aggregate_shown");
  std::string text = kBase;
  text.replace(text.find("capacity = \"10 GB\""), 18, "capacity = \"10 GB\"\naggregate_write_bw = \"5 GB/s\"");
  std::ofstream(dir / "s.toml") << text;
  const ChildResult shown = pcsim({"show", (dir / "s.toml").string()});
  REQUIRE(shown.status == 0);
  CHECK_THAT(shown.output, Catch::Contains("aggregate_write_bw = \"5 GB/s\"") && !Catch::Contains(" aggregate_read_bw"));
}

TEST_CASE("a disk's request latency, readahead, largest request and write cache are read, checked, shown and read back",
          "[cli][hostile][disk_requests]") {
  const std::string at = "capacity = \"10 GB\"";
  const auto with = [&](const std::string& keys) { return at + "\n" + keys; };
  // Bad values, each refused naming its key; a write cache and its medium's rate go together.
  refused(run_edited("latency", at, with("request_latency = \"-1 ms\"")), {"key 'hosts[0].disks[0].request_latency'", "negative"});
  refused(run_edited("read_ahead", at, with("read_ahead = \"1 KiB\"")), {"key 'hosts[0].disks[0].read_ahead'", "at least a page (4 KiB)"});
  refused(run_edited("max_request", at, with("max_request = \"-128 KiB\"")), {"key 'hosts[0].disks[0].max_request'", "negative"});
  refused(run_edited("cache_alone", at, with("write_cache = \"8 MiB\"")), {"key 'hosts[0].disks[0].write_cache'", "needs sustained_write_bw"});
  refused(run_edited("sustained_zero", at, with("write_cache = \"8 MiB\"\nsustained_write_bw = 0")),
          {"key 'hosts[0].disks[0].sustained_write_bw'", "needs sustained_write_bw"});
  refused(run_edited("sustained_alone", at, with("sustained_write_bw = \"50 MB/s\"")),
          {"key 'hosts[0].disks[0].sustained_write_bw'", "give write_cache too"});
  refused(run_edited("sustained_fast", at, with("write_cache = \"8 MiB\"\nsustained_write_bw = \"200 MB/s\"")),
          {"key 'hosts[0].disks[0].sustained_write_bw'", "must not be above write_bw"});
  // Good values: run, shown as given, and what show prints shows the same again.
  const std::string keys =
      "request_latency = \"0.1 ms\"\nread_ahead = \"128 KiB\"\nmax_request = \"1280 KiB\"\nwrite_cache = \"4 GB\"\nsustained_write_bw = \"50 MB/s\"";
  CHECK(run_edited("disk_keys_run", at, with(keys)).status == 0);
  const fs::path dir = scratch("disk_keys_shown");
  std::string text = kBase;
  text.replace(text.find(at), at.size(), with(keys));
  std::ofstream(dir / "s.toml") << text;
  const ChildResult shown = pcsim({"show", (dir / "s.toml").string()});
  REQUIRE(shown.status == 0);
  CHECK_THAT(shown.output, Catch::Contains(at + "\nrequest_latency = \"0.0001 s\"\nread_ahead = \"128 KiB\"\nmax_request = \"1280 KiB\"\n"
                                                "write_cache = \"4 GB\"\nsustained_write_bw = \"50 MB/s\"\n"));
  std::ofstream(dir / "shown.toml") << shown.output;
  const ChildResult again = pcsim({"show", (dir / "shown.toml").string()});
  REQUIRE(again.status == 0);
  CHECK(again.output.substr(again.output.find('\n')) == shown.output.substr(shown.output.find('\n')));  // but the source line
  // Unset, none is shown.
  std::ofstream(dir / "plain.toml") << kBase;
  const ChildResult plain = pcsim({"show", (dir / "plain.toml").string()});
  REQUIRE(plain.status == 0);
  for (const char* key : {"request_latency", "read_ahead", "max_request", "write_cache", "sustained_write_bw"}) {
    CHECK_THAT(plain.output, !Catch::Contains(key));
  }
  // A table amending a platform's disk keeps what it does not give, and the checks hold for the
  // disk as amended: a write_bw below the medium's rate is refused.
  std::ofstream(dir / "p.xml") << R"(<?xml version="1.0"?>
<platform version="4.1"><zone id="z" routing="Full"><host id="h" speed="1Gf"><prop id="ram" value="8GB"/>
<disk id="memory" read_bw="1000MBps" write_bw="1000MBps"><prop id="mount" value="/memory"/></disk>
<disk id="d" read_bw="100MBps" write_bw="100MBps"/></host></zone></platform>
)";
  const std::string amending = R"(profile = "paper"
platform = "p.xml"
[[hosts]]
name = "h"
[[hosts.disks]]
name = "d"
write_cache = "8 MiB"
sustained_write_bw = "50 MB/s"
[pipelines]
file_size = "1 GB"
)";
  std::ofstream(dir / "amend.toml") << amending;
  const ChildResult amended = pcsim({"show", (dir / "amend.toml").string()});
  REQUIRE(amended.status == 0);
  CHECK_THAT(amended.output, Catch::Contains("write_bw = \"100 MB/s\"\ncapacity = \"0 B\"\nwrite_cache = \"8 MiB\"\nsustained_write_bw = \"50 MB/s\"\n"));
  std::string slower = amending;
  slower.replace(slower.find("write_cache"), 0, "write_bw = \"10 MB/s\"\n");
  std::ofstream(dir / "slower.toml") << slower;
  refused(pcsim({"show", (dir / "slower.toml").string()}), {"key 'hosts[0].disks[0].sustained_write_bw'", "must not be above write_bw"});
}

TEST_CASE("a page-cache policy is one of those registered, and the switches are the kernel policy's", "[cli][hostile]") {
  refused(run_edited("policy", "[pipelines]", "[hosts.page_cache]\npolicy = \"belady\"\n[pipelines]"),
          {"key 'hosts[0].page_cache.policy'", "unknown policy 'belady'", "kernel, wrench_cache, lru"});
  refused(run_edited("switch", "[pipelines]", "[hosts.page_cache]\npolicy = \"lru\"\ntwo_touch_activation = true\n[pipelines]"),
          {"key 'hosts[0].page_cache.two_touch_activation'", "a parameter of the kernel policy", "'lru'"});
  // A switch alone chooses the kernel policy, the paper profile's values for the others.
  const fs::path dir = scratch("switch_alone");
  std::string text = kBase;
  text.replace(text.find("[pipelines]"), 11, "[hosts.page_cache]\ntwo_touch_activation = true\n[pipelines]");
  std::ofstream(dir / "s.toml") << text;
  const ChildResult shown = pcsim({"show", (dir / "s.toml").string()});
  REQUIRE(shown.status == 0);
  CHECK_THAT(shown.output, Catch::Contains("policy = \"kernel\"\n") && Catch::Contains("two_touch_activation = true\n") &&
                               Catch::Contains("reclaim_inactive_only = false\n"));
}

TEST_CASE("a policy's integer parameter is written as an integer, within its bounds, and shown as given", "[cli][hostile]") {
  refused(run_edited("batch_zero", "[pipelines]", "[hosts.page_cache]\npolicy = \"mglru\"\nrefault_batch = 0\n[pipelines]"),
          {"key 'hosts[0].page_cache.refault_batch'", "an integer from 1 to 4096, got 0"});
  refused(run_edited("batch_bool", "[pipelines]", "[hosts.page_cache]\npolicy = \"mglru\"\nrefault_batch = true\n[pipelines]"),
          {"key 'hosts[0].page_cache.refault_batch'"});
  refused(run_edited("batch_kernel", "[pipelines]", "[hosts.page_cache]\npolicy = \"kernel\"\nrefault_batch = 32\n[pipelines]"),
          {"key 'hosts[0].page_cache.refault_batch'", "a parameter of the mglru policy", "'kernel'"});
  refused(run_edited("batch_and_switch", "[pipelines]", "[hosts.page_cache]\ntwo_touch_activation = true\nrefault_batch = 32\n[pipelines]"),
          {"key 'hosts[0].page_cache.refault_batch'", "a parameter of the mglru policy", "two_touch_activation (also set)"});
  // Alone it chooses mglru; `pcsim show` writes it back as it is read.
  const fs::path dir = scratch("batch_alone");
  std::string text = kBase;
  text.replace(text.find("[pipelines]"), 11, "[hosts.page_cache]\nrefault_batch = 32\n[pipelines]");
  std::ofstream(dir / "s.toml") << text;
  const ChildResult shown = pcsim({"show", (dir / "s.toml").string()});
  REQUIRE(shown.status == 0);
  CHECK_THAT(shown.output, Catch::Contains("policy = \"mglru\"\nrefault_batch = 32\n"));
}

TEST_CASE("a bare fractional size rounds as the same size with units does", "[cli][hostile]") {
  for (const char* size : {"3.7", "\"3.7\"", "\"3.7 B\""}) {
    const fs::path dir = scratch("round");
    std::string text = kBase;
    text.replace(text.find("capacity = \"10 GB\""), 18, std::string("capacity = ") + size);
    text.replace(text.find("file_size = \"1 GB\""), 18, "file_size = 1");
    std::ofstream(dir / "s.toml") << text;
    const ChildResult r = pcsim({"show", (dir / "s.toml").string()});
    INFO(size << ": " << r.output);
    CHECK(r.status == 0);
    CHECK_THAT(r.output, Catch::Contains("capacity = \"4 B\""));
  }
}

TEST_CASE("names that would break the outputs are refused with the key", "[cli][hostile]") {
  refused(run_edited("control", "name = \"h\"", "name = \"h\\u0001\""), {"s.toml:3:8: key 'hosts[0].name'", "control character"});
  refused(run_edited("formula", "name = \"d\"", "name = \"=HYPERLINK(1)\""), {"key 'hosts[0].disks[0].name'", "formula"});
  refused(run_edited("empty", "name = \"h\"", "name = \"\""), {"key 'hosts[0].name'", "empty"});
}

TEST_CASE("the command line names what it does not know and suggests what was meant", "[cli][hostile]") {
  const ChildResult help = pcsim({"help"});
  CHECK(help.status == 0);
  for (const char* command : {"run", "show", "validate", "help"}) CHECK_THAT(help.output, Catch::Contains(command));
  const ChildResult help_run = pcsim({"help", "run"});
  CHECK(help_run.status == 0);
  CHECK_THAT(help_run.output, Catch::Contains("Usage: pcsim run") && Catch::Contains("--force") && Catch::Contains("--out"));
  refused(pcsim({"frob"}), {"unknown command 'frob'"});
  refused(pcsim({"rnu"}), {"unknown command 'rnu', did you mean 'run'?"});

  // A misspelt key is named, not the key it was meant to be reported missing.
  refused(run_edited("typo", "file_size = ", "file_sise = "), {"s.toml:13:13: unknown key 'pipelines.file_sise' (did you mean 'pipelines.file_size'?)"});
  refused(run_edited("typo2", "", "cpu_tiem = \"2 s\""), {"unknown key 'pipelines.cpu_tiem' (did you mean 'pipelines.cpu_time'?)"});

  // A bad --set value is reported at the option, not at a line of the scenario.
  const ChildResult set = run_edited("set", "", "", {"--set", "pipelines.count=\"many\""});
  refused(set, {"--set pipelines.count=\"many\": key 'pipelines.count': expected an integer"});
  CHECK_THAT(set.output, !Catch::Contains("s.toml:1:"));
  refused(run_edited("set_index", "", "", {"--set", "hosts.-1.cores=3"}), {"'-1' is not an index into an array of 1 (0 to 0)"});
  refused(run_edited("set_range", "", "", {"--set", "hosts.7.cores=3"}), {"index 7 is out of range"});
}

TEST_CASE("units people type are read, and near misses named with the right spelling", "[cli][hostile]") {
  CHECK(run_edited("gbit", "read_bw = \"100 MB/s\"", "read_bw = \"10 Gbit/s\"").status == 0);
  CHECK(run_edited("mbit", "read_bw = \"100 MB/s\"", "read_bw = \"800 Mbit/s\"").status == 0);
  CHECK(run_edited("pb", "capacity = \"10 GB\"", "capacity = \"1 PB\"").status == 0);
  CHECK(run_edited("eb", "capacity = \"10 GB\"", "capacity = \"1 EB\"").status == 0);
  refused(run_edited("gb", "memory = \"8 GB\"", "memory = \"8 gb\""), {"key 'hosts[0].memory'", "unknown size unit 'gb' (did you mean 'GB'?)"});
  refused(run_edited("gib", "memory = \"8 GB\"", "memory = \"8 gib\""), {"(did you mean 'GiB'?)"});
  refused(run_edited("gbps", "read_bw = \"100 MB/s\"", "read_bw = \"1 Gbps\""), {"(did you mean 'Gbit/s'?)"});
  refused(run_edited("mb", "read_bw = \"100 MB/s\"", "read_bw = \"100 MB\""), {"a bandwidth is a size per second (did you mean 'MB/s'?)"});
}

TEST_CASE("a file set's count and an access's epochs that would fill the memory are refused at once", "[cli][hostile][file_sets]") {
  const std::string set = "[[file_sets]]\nname = \"s\"\nsize = \"1 kB\"\ncount = ";
  const std::string access = "[[apps]]\n[[apps.tasks]]\n[[apps.tasks.access]]\nfiles = \"s\"\n";
  refused(run_edited("set_count", "", set + "1000000000000"), {"s.toml:19:9: key 'file_sets[0].count'", "more than the 2000000"});
  refused(run_edited("set_count_forced", "", set + "1000000000000", {"--force"}), {"key 'file_sets[0].count'", "more than the 1000000000"});
  refused(run_edited("epochs", "", set + "10\n" + access + "repeat = 1000000000000"), {"key 'apps[0].tasks[0].access[0].repeat'", "timeline"});
  refused(run_edited("draws", "", set + "10\n" + access + "pattern = \"random\"\nreplacement = true\ncount = 1000000000000"),
          {"key 'apps[0].tasks[0].access[0].count'", "events"});
}

TEST_CASE("an access of one file whose requests or epochs would fill the memory is refused at once, naming its key", "[cli][hostile][access]") {
  const std::string file = "[[files]]\nname = \"big\"\nsize = \"5 GB\"\n[[apps]]\n[[apps.tasks]]\n[[apps.tasks.access]]\nfile = \"big\"\n";
  refused(run_edited("bytes", "", file + "request = \"1 B\""), {"key 'apps[0].tasks[0].access[0].request'", "events"});
  refused(run_edited("file_epochs", "", file + "repeat = 1000000000000"), {"key 'apps[0].tasks[0].access[0].repeat'", "timeline"});
  refused(run_edited("file_draws", "", file + "pattern = \"random\"\nrequest = \"4 KiB\"\nreplacement = true\ncount = 1000000000000"),
          {"key 'apps[0].tasks[0].access[0].count'", "events"});
  refused(run_edited("file_slots", "", file + "pattern = \"random\"\nrequest = \"1 B\""), {"key 'apps[0].tasks[0].access[0].request'", "2^32 - 1"});
}
