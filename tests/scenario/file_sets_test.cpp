// [[file_sets]] and a task's [[...access]] tables as the loader reads them: defaults filled, every
// mistake refused with the file, line and key, huge counts refused before anything is made, and
// pcsim show writing a set as one table that reads back the same.

#include <pagecache/error.hpp>
#include <pagecache/scenario.hpp>
#include <pagecache/scenario_file.hpp>

#include <catch2/catch.hpp>

#include <chrono>
#include <string>

namespace pagecache {
namespace {

// Lines 1 to 10: a host and its disk; the set from line 11 (its keys from 13); with two keys, the
// application at 15, its task at 17, its access at 19 (files = at 20, its other keys from 21).
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

std::string scenario(const std::string& set_keys, const std::string& access_keys, const std::string& more = "") {
  return kHost + "[[file_sets]]\nname = \"images\"\n" + set_keys + "\n[[apps]]\nname = \"trainer\"\n[[apps.tasks]]\nname = \"train\"\n" +
         "[[apps.tasks.access]]\nfiles = \"images\"\n" + access_keys + "\n" + more;
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

TEST_CASE("a file set and an access over it take their defaults", "[scenario][file_sets]") {
  const Scenario s = parse_scenario(scenario("count = 10\nsize = \"100 kB\"", ""), "s.toml");
  REQUIRE(s.file_sets.size() == 1);
  CHECK(s.file_sets[0].count == 10);
  CHECK(s.file_sets[0].size == 100'000);
  CHECK(s.file_sets[0].host == "node");
  CHECK(s.file_sets[0].disk == "ssd");
  CHECK_FALSE(s.file_sets[0].cached);
  CHECK(s.files.empty());  // a set is not its files
  const AccessSpec& a = s.apps.at(0).tasks.at(0).accesses.at(0);
  CHECK(a.file_set == "images");
  CHECK(a.pattern == AccessPattern::Sequential);
  CHECK(a.seed == 0);
  CHECK_FALSE(a.replacement);
  CHECK(a.count == 10);  // the set's
  CHECK(a.repeat == 1);
}

TEST_CASE("an access's keys are read as written", "[scenario][file_sets]") {
  const Scenario s =
      parse_scenario(scenario("count = 10\nsize = \"1 MB\"", "pattern = \"random\"\nseed = 7\nreplacement = true\ncount = 25\nrepeat = 4"), "s.toml");
  const AccessSpec& a = s.apps.at(0).tasks.at(0).accesses.at(0);
  CHECK(a.pattern == AccessPattern::Random);
  CHECK(a.seed == 7);
  CHECK(a.replacement);
  CHECK(a.count == 25);  // with replacement, more draws than files
  CHECK(a.repeat == 4);
}

TEST_CASE("mistakes in a file set or an access are refused with the file, line and key", "[scenario][file_sets]") {
  const std::string ok = "count = 10\nsize = \"1 MB\"";
  CHECK_THAT(refusal(scenario("size = \"1 MB\"", "")), Catch::Contains("s.toml:11:") && Catch::Contains("count"));
  CHECK_THAT(refusal(scenario("count = 0\nsize = \"1 MB\"", "")), Catch::Contains("s.toml:13:9: key 'file_sets[0].count'"));
  CHECK_THAT(refusal(scenario(ok + "\nhost = \"nowhere\"", "")), Catch::Contains("key 'file_sets[0].host'") && Catch::Contains("no host"));
  CHECK_THAT(refusal(scenario(ok + "\ndisk = \"tape\"", "")), Catch::Contains("key 'file_sets[0].disk'"));
  CHECK_THAT(refusal(scenario(ok + "\nsise = 3", "")), Catch::Contains("s.toml:15:8: unknown key 'file_sets[0].sise'"));
  CHECK_THAT(refusal(scenario("count = 10\nsize = \"200 GB\"", "")), Catch::Contains("key 'file_sets[0].size'") && Catch::Contains("do not fit"));
  CHECK_THAT(refusal(scenario("count = 1000\nsize = \"1 GB\"", "")), Catch::Contains("more than its capacity"));
  // The access: lines 19 on.
  CHECK_THAT(refusal(scenario(ok, "pattern = \"shuffled\"")), Catch::Contains("s.toml:21:11: key 'apps[0].tasks[0].access[0].pattern'"));
  CHECK_THAT(refusal(scenario(ok, "replacement = true")),
             Catch::Contains("key 'apps[0].tasks[0].access[0].replacement'") && Catch::Contains("pattern = \"random\""));
  CHECK_THAT(refusal(scenario(ok, "pattern = \"random\"\ncount = 11")),
             Catch::Contains("s.toml:22:9: key 'apps[0].tasks[0].access[0].count'") && Catch::Contains("at most once per epoch"));
  CHECK_THAT(refusal(scenario(ok, "repeat = 0")), Catch::Contains("key 'apps[0].tasks[0].access[0].repeat'"));
  CHECK_THAT(refusal(scenario(ok, "seed = -1")), Catch::Contains("key 'apps[0].tasks[0].access[0].seed'"));
  CHECK_THAT(refusal(scenario(ok, "file = \"x\"")), Catch::Contains("s.toml:21:8: key 'apps[0].tasks[0].access[0].file'") && Catch::Contains("not both"));
  CHECK_THAT(refusal(scenario(ok, "request = \"4 KiB\"")),
             Catch::Contains("s.toml:21:11: key 'apps[0].tasks[0].access[0].request'") && Catch::Contains("access of one file"));
  CHECK_THAT(refusal(scenario(ok, "").replace(scenario(ok, "").find("files = \"images\""), 16, "files = \"videos\"")),
             Catch::Contains("s.toml:20:9: key 'apps[0].tasks[0].access[0].files'") && Catch::Contains("no file set named 'videos'"));
}

TEST_CASE("a file set's name is no file's, nor a file's name that of a set's member", "[scenario][file_sets]") {
  const std::string ok = "count = 10\nsize = \"1 MB\"";
  CHECK_THAT(refusal(scenario(ok, "", "[[files]]\nname = \"images\"\nsize = \"1 MB\"\n")),
             Catch::Contains("key 'file_sets[0].name'") && Catch::Contains("a file is named 'images' too"));
  CHECK_THAT(refusal(scenario(ok, "", "[[files]]\nname = \"images/9\"\nsize = \"1 MB\"\n")),
             Catch::Contains("key 'files[0].name'") && Catch::Contains("file set 'images'"));
  // Not a member: past the count, or not a number of the set's form.
  for (const char* name : {"images/10", "images/07", "images/x", "images"}) {
    if (std::string(name) == "images") continue;
    CHECK_NOTHROW(parse_scenario(scenario(ok, "", std::string("[[files]]\nname = \"") + name + "\"\nsize = \"1 MB\"\n"), "s.toml"));
  }
  CHECK_THAT(refusal(scenario(ok, "", "[[file_sets]]\nname = \"images\"\ncount = 1\nsize = \"1 MB\"\n")),
             Catch::Contains("two file sets named 'images'"));
}

TEST_CASE("huge counts and epochs are refused at once, naming their key", "[scenario][file_sets]") {
  const auto started = std::chrono::steady_clock::now();
  CHECK_THAT(refusal(scenario("count = 1000000000000\nsize = \"1 B\"", "")),
             Catch::Contains("s.toml:13:9: key 'file_sets[0].count'") && Catch::Contains("more than the 2000000"));
  CHECK_THAT(refusal(scenario("count = 10\nsize = \"1 kB\"", "repeat = 1000000000000")),
             Catch::Contains("key 'apps[0].tasks[0].access[0].repeat'"));
  CHECK_THAT(refusal(scenario("count = 10\nsize = \"1 kB\"", "pattern = \"random\"\nreplacement = true\ncount = 1000000000000")),
             Catch::Contains("key 'apps[0].tasks[0].access[0].count'") && Catch::Contains("events"));
  // Epochs make timeline rows: a million epochs of one small file is refused by its rows.
  CHECK_THAT(refusal(scenario("count = 1\nsize = \"1 kB\"", "repeat = 5000000")),
             Catch::Contains("key 'apps[0].tasks[0].access[0].repeat'") && Catch::Contains("timeline"));
  CHECK(std::chrono::steady_clock::now() - started < std::chrono::seconds(2));
}

TEST_CASE("pcsim show writes a file set as one table and its accesses in full, and they read back the same", "[scenario][file_sets][show]") {
  const Scenario s = parse_scenario(
      scenario("count = 1000000\nsize = \"100 B\"\ncached = true", "pattern = \"random\"\nseed = 3\nrepeat = 2"), "s.toml");
  const std::string shown = to_toml(s);
  CHECK(shown.find("[[file_sets]]\nname = \"images\"\ncount = 1000000\nsize = \"100 B\"\nhost = \"node\"\ndisk = \"ssd\"\ncached = true\n") !=
        std::string::npos);
  CHECK(shown.find("images/0") == std::string::npos);
  CHECK(shown.find("[[apps.tasks.access]]\nfiles = \"images\"\npattern = \"random\"\nseed = 3\nreplacement = false\ncount = 1000000\nrepeat = 2\n") !=
        std::string::npos);
  const Scenario back = parse_scenario(shown, "shown.toml");
  CHECK(to_toml(back).substr(to_toml(back).find('\n')) == shown.substr(shown.find('\n')));
}

}  // namespace
}  // namespace pagecache
