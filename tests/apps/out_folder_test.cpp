// pcsim run --out, run as a user would: the folder it writes is one it made (marked by
// .pcsim-output), an empty one or a new one; anything else is refused with exit status 2 before
// simulating, and nothing in it changes. Concurrent runs: out_folder_concurrency.sh.
#include "support/pcsim_cli.hpp"

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <sys/stat.h>

namespace fs = std::filesystem;
using namespace pagecache::testing;

namespace {

const std::set<std::string> kOutputs = {".pcsim-output", "cache.csv", "memory.csv", "report.html", "summary.json", "timeline.csv", "timing.json"};

// Everything below `dir` (links not followed), by relative path: a folder, a file with its
// size and contents, or a link with its target.
std::map<std::string, std::string> listing(const fs::path& dir) {
  std::map<std::string, std::string> out;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    const std::string name = fs::relative(entry.path(), dir).string();
    if (entry.is_symlink()) out[name] = "link to " + fs::read_symlink(entry.path()).string();
    else if (entry.is_directory()) out[name] = "folder";
    else out[name] = fmt::format("{} bytes: {}", entry.file_size(), slurp(entry.path()));
  }
  return out;
}

void write(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << text;
}

// The small fast scenario, reading a file of `size`, as dir/name.
fs::path scenario(const fs::path& dir, const std::string& name = "s.toml", const std::string& size = "1 GB") {
  std::string text = std::string(kPlatform) + kWorkload;
  text.replace(text.find("size = \"1 GB\""), 13, fmt::format("size = \"{}\"", size));
  write(dir / name, text);
  return dir / name;
}

Outcome run(const fs::path& scenario_file, const std::string& out, const fs::path& cwd = {}) {
  return pcsim(fmt::format("run '{}' --out '{}' --quiet", scenario_file.string(), out), cwd);
}

// Exit status 2 and a message naming the folder and why, with nothing removed.
void expect_refused(const Outcome& o, const fs::path& folder, const std::string& why) {
  INFO(o.output);
  CHECK(o.status == 2);
  CHECK_THAT(o.output, Catch::Contains(folder.string()) && Catch::Contains(why) &&
                           Catch::Contains("nothing was removed"));
}

}  // namespace

TEST_CASE("pcsim refuses an --out folder holding someone's files, and every file stays as it was", "[cli][out]") {
  const fs::path dir = scratch("out-project");
  const fs::path project = dir / "proj";
  write(project / "README.md", "# my project\n");
  write(project / "src" / "main.c", "int main(void) { return 0; }\n");
  write(project / "summary.json", "{\"mine\": true}\n");  // a name pcsim uses, in a folder it did not make
  fs::create_directories(project / "build");
  const auto before = listing(project);
  expect_refused(run(scenario(dir), project.string()), project, "holds 'README.md', which pcsim did not write");
  CHECK(listing(project) == before);
  CHECK(names(dir) == std::set<std::string>{"proj", "s.toml"});  // no staging folder left
}

TEST_CASE("pcsim refuses the --out folder before simulating, not after", "[cli][out]") {
  // This scenario cannot be simulated (1 GB of buffers on a 0.5 GB host: exit status 1 once it
  // runs); refusing the folder first gives exit status 2 without running it.
  const fs::path dir = scratch("out-before");
  std::string text = std::string(kPlatform) + kWorkload;
  text.replace(text.find("memory = \"8 GB\""), 15, "memory = \"500 MB\"");
  write(dir / "impossible.toml", text);
  write(dir / "proj" / "notes.txt", "mine\n");
  const Outcome o = run(dir / "impossible.toml", (dir / "proj").string());
  expect_refused(o, dir / "proj", "holds 'notes.txt'");
  CHECK_THAT(o.output, !Catch::Contains("simulation failed"));
}

TEST_CASE("pcsim refuses --out .. from a subfolder, and the parent and its other folders stay", "[cli][out]") {
  const fs::path dir = scratch("out-dotdot");
  const fs::path project = dir / "proj";
  scenario(project / "sub");
  write(project / "sibling" / "data.csv", "1,2,3\n");
  const auto before = listing(project);
  expect_refused(run("s.toml", "..", project / "sub"), project, "is the current folder or one above it");
  CHECK(listing(project) == before);
}

TEST_CASE("pcsim refuses --out . even where the current folder is empty", "[cli][out]") {
  const fs::path dir = scratch("out-dot");
  const fs::path here = dir / "here";
  fs::create_directories(here);
  struct stat st_before{};
  REQUIRE(::stat(here.c_str(), &st_before) == 0);
  expect_refused(run(scenario(dir), ".", here), here, "is the current folder or one above it");
  struct stat st_after{};
  REQUIRE(::stat(here.c_str(), &st_after) == 0);
  CHECK(st_after.st_ino == st_before.st_ino);  // the same folder, not one renamed in its place
  CHECK(fs::is_empty(here));
}

TEST_CASE("pcsim refuses an --out folder that holds the scenario", "[cli][out]") {
  const fs::path dir = scratch("out-scenario");
  const fs::path file = scenario(dir / "sc");
  const auto before = listing(dir / "sc");
  expect_refused(run(file, (dir / "sc").string()), dir / "sc", "holds the scenario file");
  CHECK(listing(dir / "sc") == before);
}

TEST_CASE("pcsim refuses an --out that is a regular file, which stays as it was", "[cli][out]") {
  const fs::path dir = scratch("out-file");
  write(dir / "f.txt", "keep me\n");
  expect_refused(run(scenario(dir), (dir / "f.txt").string()), dir / "f.txt", "is not a folder");
  CHECK(fs::is_regular_file(fs::symlink_status(dir / "f.txt")));
  CHECK(slurp(dir / "f.txt") == "keep me\n");
}

TEST_CASE("pcsim refuses an empty --out with a message, not a filesystem error", "[cli][out]") {
  const fs::path dir = scratch("out-empty-name");
  const Outcome o = run(scenario(dir), "");
  INFO(o.output);
  CHECK(o.status == 2);
  CHECK_THAT(o.output, Catch::Contains("--out is empty") && !Catch::Contains("filesystem error"));
  CHECK(names(dir) == std::set<std::string>{"s.toml"});
}

TEST_CASE("a folder pcsim made is replaced by the next run's outputs, until someone adds a file to it", "[cli][out]") {
  const fs::path dir = scratch("out-replace");
  const fs::path out = dir / "runs" / "out";  // the folders above it are made too
  const fs::path small = scenario(dir, "small.toml", "1 GB");
  const fs::path large = scenario(dir, "large.toml", "2 GB");
  REQUIRE(run(large, (dir / "reference").string()).status == 0);
  REQUIRE(run(small, out.string()).status == 0);
  CHECK(names(out) == kOutputs);
  CHECK(slurp(out / ".pcsim-output") == "written by pcsim; pcsim run --out may replace this folder\n");

  const Outcome o = run(large, out.string());
  INFO(o.output);
  REQUIRE(o.status == 0);
  CHECK(names(out) == kOutputs);
  for (const std::string& name : kOutputs) {
    INFO(name);
    if (name != "timing.json") CHECK(slurp(out / name) == slurp(dir / "reference" / name));
  }
  CHECK(names(dir / "runs") == std::set<std::string>{"out"});  // nothing set aside, no staging left

  write(out / "notes.txt", "my conclusions\n");
  const auto before = listing(out);
  expect_refused(run(small, out.string()), out, "holds 'notes.txt', which pcsim did not write");
  CHECK(listing(out) == before);
}

TEST_CASE("a folder pcsim made is refused once a user put a folder in it or made an output a link", "[cli][out]") {
  const fs::path dir = scratch("out-marked");
  const fs::path file = scenario(dir);
  const fs::path out = dir / "out";
  REQUIRE(run(file, out.string()).status == 0);
  write(out / "plots" / "makespan.png", "PNG");
  auto before = listing(out);
  expect_refused(run(file, out.string()), out, "holds 'plots', which pcsim did not write");
  CHECK(listing(out) == before);

  fs::remove_all(out / "plots");
  write(dir / "precious.csv", "mine\n");
  fs::remove(out / "timeline.csv");
  fs::create_symlink(dir / "precious.csv", out / "timeline.csv");
  before = listing(out);
  expect_refused(run(file, out.string()), out, "holds 'timeline.csv', which pcsim did not write");
  CHECK(listing(out) == before);
  CHECK(slurp(dir / "precious.csv") == "mine\n");
}

TEST_CASE("a folder of pcsim's outputs without the marker (an older pcsim's) is refused", "[cli][out]") {
  const fs::path dir = scratch("out-unmarked");
  const fs::path file = scenario(dir);
  REQUIRE(run(file, (dir / "out").string()).status == 0);
  fs::remove(dir / "out" / ".pcsim-output");
  const auto before = listing(dir / "out");
  expect_refused(run(file, (dir / "out").string()), dir / "out", "holds no .pcsim-output marker");
  CHECK(listing(dir / "out") == before);
}

TEST_CASE("pcsim refuses an --out that is a symbolic link, even to a folder it made, and writes nothing through it", "[cli][out]") {
  const fs::path dir = scratch("out-link");
  const fs::path file = scenario(dir);
  REQUIRE(run(file, (dir / "real").string()).status == 0);
  fs::create_directory_symlink(dir / "real", dir / "link");
  fs::create_directory_symlink(dir / "nowhere", dir / "dangling");
  const auto before = listing(dir);
  expect_refused(run(file, (dir / "link").string()), dir / "link", "is a symbolic link");
  expect_refused(run(file, (dir / "dangling").string()), dir / "dangling", "is a symbolic link");
  CHECK(listing(dir) == before);
}

TEST_CASE("an empty --out folder receives the outputs and keeps its permissions", "[cli][out]") {
  const fs::path dir = scratch("out-empty-folder");
  const fs::path out = dir / "out";
  fs::create_directories(out);
  fs::permissions(out, fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec);
  const Outcome o = run(scenario(dir), out.string());
  INFO(o.output);
  REQUIRE(o.status == 0);
  CHECK(names(out) == kOutputs);
  CHECK((fs::status(out).permissions() & fs::perms::all) == (fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec));
}

TEST_CASE("pcsim validate --json refuses a folder before validating", "[cli][out]") {
  const fs::path dir = scratch("out-json-folder");
  write(dir / "results" / "keep.txt", "mine\n");
  const Outcome o = pcsim(fmt::format("validate --json '{}'", (dir / "results").string()));
  INFO(o.output);
  CHECK(o.status == 2);
  CHECK_THAT(o.output, Catch::Contains("is a folder") && !Catch::Contains("exp1"));
  CHECK(slurp(dir / "results" / "keep.txt") == "mine\n");
}
