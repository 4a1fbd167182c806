// A task's [[...access]] of parts of one file (file = "NAME") as the loader reads it: defaults
// filled from the file and the task, every rule refused with the file, line and key, hostile
// sizes refused by the estimate at once, and pcsim show writing the pattern's keys only.

#include <pagecache/error.hpp>
#include <pagecache/scenario.hpp>
#include <pagecache/scenario_file.hpp>

#include <catch2/catch.hpp>

#include <chrono>
#include <string>

namespace pagecache {
namespace {

// Lines 1 to 10: a host and its disk; the file at 11 to 13; the application at 14, its task at
// 16 (its keys at 17), its access at 18 (file = at 19, its other keys from 20).
const std::string kHost = R"([[hosts]]
name = "node"
memory = "1 GB"
memory_read_bw = "10 GB/s"
memory_write_bw = "10 GB/s"
[[hosts.disks]]
name = "ssd"
read_bw = "500 MB/s"
write_bw = "400 MB/s"
capacity = "100 GB"
)";

std::string scenario(const std::string& access_keys, const std::string& task_keys = "chunk_size = \"1 MB\"", const std::string& size = "10 MB") {
  return kHost + "[[files]]\nname = \"data\"\nsize = \"" + size + "\"\n[[apps]]\nname = \"app\"\n[[apps.tasks]]\n" + task_keys +
         "\n[[apps.tasks.access]]\nfile = \"data\"\n" + access_keys + "\n";
}

std::string refusal(const std::string& text) {
  try {
    parse_scenario(text, "s.toml");
  } catch (const ConfigError& e) {
    return e.what();
  }
  FAIL("accepted: " << text);
  return {};
}

const AccessSpec& access_of(const Scenario& s) { return s.apps.at(0).tasks.at(0).accesses.at(0); }

TEST_CASE("an access of one file takes its defaults from the file and the task", "[scenario][access]") {
  const Scenario s = parse_scenario(scenario(""), "s.toml");
  const AccessSpec& a = access_of(s);
  CHECK(a.file == "data");
  CHECK(a.file_set.empty());
  CHECK(a.pattern == AccessPattern::Sequential);
  CHECK(a.mode == AccessMode::Read);
  CHECK(a.advice == AccessAdvice::Normal);
  CHECK(a.request == 1'000'000);  // the task's chunk size
  CHECK(a.offset == 0);
  CHECK(a.length == 10'000'000);  // to the file's end
  CHECK(a.count == 10);           // each request of the region once
  CHECK(a.repeat == 1);
  // Strided: as many as fit; random: each slot once.
  CHECK(access_of(parse_scenario(scenario("pattern = \"strided\"\nrequest = \"1 MB\"\nstride = \"3 MB\""), "s.toml")).count == 4);
  CHECK(access_of(parse_scenario(scenario("pattern = \"random\"\nrequest = \"3 MB\""), "s.toml")).count == 4);
}

TEST_CASE("an access of one file reads its keys as written", "[scenario][access]") {
  const AccessSpec a = access_of(parse_scenario(
      scenario("pattern = \"random\"\nrequest = \"4 KiB\"\noffset = \"1 MB\"\nlength = \"2 MB\"\nseed = 9\nreplacement = true\ncount = 1000\n"
               "repeat = 3\nadvice = \"random\""),
      "s.toml"));
  CHECK(a.pattern == AccessPattern::Random);
  CHECK(a.request == 4096);
  CHECK(a.offset == 1'000'000);
  CHECK(a.length == 2'000'000);
  CHECK(a.seed == 9);
  CHECK(a.replacement);
  CHECK(a.count == 1000);  // with replacement, more draws than the 489 slots
  CHECK(a.repeat == 3);
  CHECK(a.advice == AccessAdvice::Random);
  const AccessSpec r = access_of(parse_scenario(scenario("pattern = \"ranges\"\nranges = [[0, 4096], [\"1 MB\", \"8 KiB\"]]\nmode = \"write\""), "s.toml"));
  CHECK(r.pattern == AccessPattern::Ranges);
  CHECK(r.mode == AccessMode::Write);
  REQUIRE(r.ranges.size() == 2);
  CHECK(r.ranges[1] == std::pair<std::int64_t, std::int64_t>{1'000'000, 8192});
  const AccessSpec w = access_of(parse_scenario(scenario("mode = \"append\"\noffset = \"4 MB\"\nrequest = \"64 kB\""), "s.toml"));
  CHECK(w.mode == AccessMode::Append);
  CHECK(w.length == 6'000'000);
  CHECK(w.count == 94);
}

TEST_CASE("every rule of an access of one file is refused with the file, line and key", "[scenario][access]") {
  const std::string key = "key 'apps[0].tasks[0].access[0].";
  const auto refused = [&](const std::string& keys, const std::string& where, const std::string& what) {
    INFO(keys);
    CHECK_THAT(refusal(scenario(keys)), Catch::Contains(where + ": " + key) && Catch::Contains(what));
  };
  refused("pattern = \"zigzag\"", "s.toml:20:11", "\"strided\" or \"ranges\"");
  refused("mode = \"delete\"", "s.toml:20:8", "\"write\" or \"append\"");
  refused("advice = \"willneed\"", "s.toml:20:10", "\"sequential\" or \"random\"");
  refused("mode = \"write\"\nadvice = \"random\"", "s.toml:21:10", "for reads");
  refused("mode = \"append\"\npattern = \"random\"", "s.toml:21:11", "pattern = \"sequential\"");
  refused("request = 0", "s.toml:20:11", "must be > 0");
  refused("offset = \"10 MB\"", "s.toml:20:10", "not within file 'data'");
  refused("length = 0", "s.toml:20:10", "must be > 0");
  refused("offset = \"4 MB\"\nlength = \"7 MB\"", "s.toml:21:10", "past the end of file 'data'");
  refused("pattern = \"strided\"\nstride = \"100 kB\"", "s.toml:21:10", "shorter than a request");
  refused("pattern = \"strided\"\nstride = \"3 MB\"\ncount = 5", "s.toml:22:9", "more than the 4 that fit");
  refused("pattern = \"strided\"\nrequest = \"2 MB\"\nstride = \"2 MB\"\nlength = \"1 MB\"", "s.toml:23:10", "no request fits");
  refused("stride = \"2 MB\"", "s.toml:20:10", "a key of pattern = \"strided\"");
  refused("pattern = \"random\"\ncount = 11", "s.toml:21:9", "random without replacement");
  refused("mode = \"append\"\ncount = 11", "s.toml:21:9", "an append");
  refused("count = 0", "s.toml:20:9", "must be >= 1");
  refused("replacement = true", "s.toml:20:15", "pattern = \"random\"");
  refused("seed = 4", "s.toml:20:8", "pattern = \"random\"");
  refused("pattern = \"random\"\nseed = -1", "s.toml:21:8", "must be >= 0");
  refused("repeat = 0", "s.toml:20:10", "must be >= 1");
  refused("ranges = [[0, 1]]", "s.toml:20:10", "pattern = \"ranges\"");
  refused("pattern = \"ranges\"\nranges = [[0, 1]]\noffset = 0", "s.toml:22:10", "not a key of pattern = \"ranges\"");
  refused("pattern = \"ranges\"\nranges = []", "s.toml:21:10", "at least one");
  refused("pattern = \"ranges\"\nranges = [[0]]", "s.toml:21:10", "ranges[0]: expected [offset, length]");
  refused("pattern = \"ranges\"\nranges = [[0, 1], [\"9 MB\", \"2 MB\"]]", "s.toml:21:10", "ranges[1]: 2000000 bytes at 9000000 are not within");
  refused("pattern = \"ranges\"\nranges = [[0, -1]]", "s.toml:21:10", "must not be negative");
  refused("pattern = \"ranges\"\nranges = [[0, \"a lot\"]]", "s.toml:21:10", "ranges[0]");
  refused("pattern = \"ranges\"\nranges = [[0, 0.5]]", "s.toml:21:10", "expected a size");
  refused("files = \"x\"", "s.toml:19:8", "not both");
  CHECK_THAT(refusal(scenario("requests = 4")), Catch::Contains("s.toml:20:12: unknown key 'apps[0].tasks[0].access[0].requests'") &&
                                                  Catch::Contains("did you mean"));
  // A missing key names the table.
  CHECK_THAT(refusal(scenario("pattern = \"strided\"")), Catch::Contains("s.toml:18:1") && Catch::Contains("missing key 'stride'"));
  CHECK_THAT(refusal(scenario("pattern = \"ranges\"")), Catch::Contains("s.toml:18:1") && Catch::Contains("missing key 'ranges'"));
  CHECK_THAT(refusal(scenario("").replace(scenario("").find("file = \"data\""), 13, "")), Catch::Contains("s.toml:18:1") &&
                                                                                             Catch::Contains("files = \"SET\"") &&
                                                                                             Catch::Contains("file = \"NAME\""));
  CHECK_THAT(refusal(scenario("").replace(scenario("").find("file = \"data\""), 13, "file = \"other\"")),
             Catch::Contains("s.toml:19:8: " + key + "file'") && Catch::Contains("no file named 'other'"));
  // The task's keys: appends through O_DIRECT are not modelled (reads and writes in place are).
  CHECK_THAT(refusal(scenario("mode = \"append\"", "direct_io = true")),
             Catch::Contains("s.toml:17:13: key 'apps[0].tasks[0].direct_io'") && Catch::Contains("not modelled"));
  CHECK_NOTHROW(parse_scenario(scenario("mode = \"write\"", "direct_io = true"), "s.toml"));
}

TEST_CASE("a random pattern of more than 2^32 slots, and hostile sizes, are refused at once naming their key", "[scenario][access]") {
  const auto started = std::chrono::steady_clock::now();
  CHECK_THAT(refusal(scenario("pattern = \"random\"\nrequest = \"1 B\"", "", "90 TB")),
             Catch::Contains("s.toml:21:11: key 'apps[0].tasks[0].access[0].request'") && Catch::Contains("2^32 - 1"));
  // 10^15 requests of 1 B over a 1 PB file: refused by the estimate, naming the request size.
  const std::string big = kHost + "[[files]]\nname = \"data\"\nsize = \"1 PB\"\n";
  const std::string huge_disk = "capacity = \"2 PB\"";
  auto text = scenario("request = \"1 B\"", "", "1 PB");
  text.replace(text.find("capacity = \"100 GB\""), 19, huge_disk);
  CHECK_THAT(refusal(text), Catch::Contains("key 'apps[0].tasks[0].access[0].request'") && Catch::Contains("events"));
  CHECK_THAT(refusal(scenario("repeat = 1000000000000")), Catch::Contains("key 'apps[0].tasks[0].access[0].repeat'"));
  CHECK_THAT(refusal(scenario("pattern = \"random\"\nrequest = \"4 KiB\"\nreplacement = true\ncount = 1000000000000")),
             Catch::Contains("key 'apps[0].tasks[0].access[0].count'") && Catch::Contains("events"));
  CHECK(std::chrono::steady_clock::now() - started < std::chrono::seconds(2));
}

TEST_CASE("a file accessed by part is on the task's own host", "[scenario][access]") {
  const std::string two_hosts = scenario("") + R"([[hosts]]
name = "other"
memory = "1 GB"
memory_read_bw = "10 GB/s"
memory_write_bw = "10 GB/s"
[[hosts.disks]]
name = "ssd"
read_bw = "500 MB/s"
write_bw = "400 MB/s"
[[links]]
name = "net"
bandwidth = "1 GB/s"
hosts = ["node", "other"]
)";
  CHECK_NOTHROW(parse_scenario(two_hosts, "s.toml"));
  std::string remote = two_hosts;
  remote.replace(remote.find("name = \"app\""), 12, "name = \"app\"\nhost = \"other\"");
  CHECK_THAT(refusal(remote), Catch::Contains("s.toml: application 'app', task '1': file 'data' is on host 'node'") &&
                                  Catch::Contains("the task's own host"));
}

TEST_CASE("a workflow task accessing a file by part runs only where the file is", "[scenario][access]") {
  const std::string other = R"([[hosts]]
name = "other"
memory = "1 GB"
memory_read_bw = "10 GB/s"
memory_write_bw = "10 GB/s"
[[hosts.disks]]
name = "ssd"
read_bw = "500 MB/s"
write_bw = "400 MB/s"
[[links]]
name = "net"
bandwidth = "1 GB/s"
hosts = ["node", "other"]
)";
  const std::string workflow = kHost + other + "[[files]]\nname = \"data\"\nsize = \"10 MB\"\n[workflow]\nhosts = [\"node\", \"other\"]\n" +
                               "[[workflow.tasks]]\nname = \"scan\"\n%s[[workflow.tasks.access]]\nfile = \"data\"\n";
  const auto with = [&](const std::string& task_keys) {
    std::string text = workflow;
    text.replace(text.find("%s"), 2, task_keys);
    return text;
  };
  CHECK_THAT(refusal(with("")), Catch::Contains("workflow 'workflow', task 'scan': file 'data' is on host 'node' and the task may run on 'other'"));
  const Scenario s = parse_scenario(with("host = \"node\"\n"), "s.toml");
  CHECK(s.workflows.at(0).tasks.at(0).accesses.at(0).file == "data");
}

TEST_CASE("pcsim show writes an access of one file with its pattern's keys, and it reads back the same", "[scenario][access][show]") {
  for (const std::string keys : {"pattern = \"strided\"\nrequest = \"64 KiB\"\nstride = \"1 MB\"\nrepeat = 2",
                                 "pattern = \"random\"\nrequest = \"4 KiB\"\nseed = 5\nadvice = \"random\"\nreshuffle = false\ninvalidate = true",
                                 "pattern = \"ranges\"\nranges = [[0, 4096], [\"1 MB\", \"2 MB\"]]\nmode = \"write\"",
                                 "mode = \"append\"\noffset = \"5 MB\""}) {
    INFO(keys);
    const std::string shown = to_toml(parse_scenario(scenario(keys), "s.toml"));
    const Scenario back = parse_scenario(shown, "shown.toml");
    CHECK(to_toml(back).substr(to_toml(back).find('\n')) == shown.substr(shown.find('\n')));
  }
  const std::string strided = to_toml(parse_scenario(scenario("pattern = \"strided\"\nrequest = \"64 KiB\"\nstride = \"1 MB\""), "s.toml"));
  CHECK(strided.find("[[apps.tasks.access]]\nfile = \"data\"\npattern = \"strided\"\nmode = \"read\"\nadvice = \"normal\"\nrequest = \"64 KiB\"\n"
                     "offset = \"0 B\"\nlength = \"10 MB\"\nstride = \"1 MB\"\ncount = 10\ninvalidate = false\nrepeat = 1\n") != std::string::npos);
  CHECK(strided.find("seed") == std::string::npos);
  const std::string ranges = to_toml(parse_scenario(scenario("pattern = \"ranges\"\nranges = [[0, 4096]]\nmode = \"write\""), "s.toml"));
  CHECK(ranges.find("ranges = [[\"0 B\", \"4 KiB\"]]\ninvalidate = false\nrepeat = 1\n") != std::string::npos);
  CHECK(ranges.find("advice") == std::string::npos);
  CHECK(ranges.find("offset") == std::string::npos);
}

}  // namespace
}  // namespace pagecache
