// Every output path pcsim is given, tried as a hostile user would (issue 33): devices, FIFOs,
// links and folders given to --json, --report and calibrate --out; --out names at the file
// system's limit; pcsim killed while it writes.
#include "support/files.hpp"
#include "support/pcsim_cli.hpp"

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <array>
#include <chrono>
#include <csignal>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

namespace fs = std::filesystem;
using pagecache::testing::names;
using pagecache::testing::read_fifo;
using pagecache::testing::pcsim;
using pagecache::testing::scratch;
using pagecache::testing::slurp;

namespace {

fs::file_type type_of(const fs::path& p) { return fs::symlink_status(p).type(); }


const std::string kTwoReaders = (fs::path(PCSIM_TEST_DIR) / "golden" / "two_readers.toml").string();

// Names in `dir` that a staging folder or temporary file of pcsim's would have.
std::vector<std::string> leftovers(const fs::path& dir) {
  std::vector<std::string> out;
  for (const auto& name : names(dir)) {
    if (std::regex_search(name, std::regex(R"(\.tmp-|\.old-)"))) out.push_back(name);
  }
  return out;
}

}  // namespace

TEST_CASE("validate --json and --report write through a character device and a FIFO, and leave them as they were",
          "[cli][outputs][validate]") {
  const fs::path dir = scratch("paths-devices");
  if (::geteuid() == 0) {
    REQUIRE(::mknod((dir / "mynull").c_str(), S_IFCHR | 0666, makedev(1, 3)) == 0);
  } else {
    fs::create_symlink("/dev/null", dir / "mynull");
  }
  const fs::file_type before = type_of(dir / "mynull");
  REQUIRE(::mkfifo((dir / "fifo").c_str(), 0666) == 0);
  std::string received;
  std::thread reader([&] { received = read_fifo(dir / "fifo"); });
  const auto o = pcsim("validate --json mynull --report fifo", dir);
  reader.join();
  INFO(o.output);
  CHECK(o.status == 0);
  CHECK(type_of(dir / "mynull") == before);
  CHECK(type_of(dir / "fifo") == fs::file_type::fifo);
  CHECK_THAT(received, Catch::StartsWith("<!DOCTYPE html>"));
  CHECK(names(dir) == std::set<std::string>{"fifo", "mynull"});
}

TEST_CASE("validate --json /dev/stdout prints the JSON among pcsim's output and replaces nothing", "[cli][outputs][validate]") {
  const fs::path dir = scratch("paths-stdout");
  const auto o = pcsim(fmt::format("validate --json /dev/stdout --report '{}'", (dir / "r.html").string()));
  INFO(o.output.substr(0, 2000));
  CHECK(o.status == 0);
  CHECK_THAT(o.output, Catch::Contains("\"case\": \"exp1_20gb\""));
  CHECK(type_of("/dev/stdout") == fs::file_type::symlink);
}

TEST_CASE("an output option given a folder, a link to nothing or a missing folder is refused by its own name, before any work",
          "[cli][outputs]") {
  const fs::path dir = scratch("paths-refused");
  fs::create_directories(dir / "adir");
  fs::create_symlink(dir / "nothing", dir / "dangling");
  fs::create_symlink("loop", dir / "loop");
  struct Case {
    std::string args;
    std::string message;
  };
  const std::vector<Case> cases = {
      {"validate --report adir", "pcsim: --report adir: is a folder; name a file"},
      {"validate --json adir", "pcsim: --json adir: is a folder; name a file"},
      {"validate --json dangling", "pcsim: --json dangling: is a link to nothing"},
      {"validate --json no/v.json", "pcsim: --json no/v.json: the folder no does not exist"},
      {"calibrate --dir . --out adir", "pcsim: --out adir: is a folder; name a file"},
      {"validate --json loop", "pcsim: --json loop: is a link that leads back to itself"},
      {"validate --json ''", "pcsim: --json : no file named"},
      {"validate --report ''", "pcsim: --report : no file named"},
      {"sweep merge nowhere --csv ''", "pcsim: --csv : no file named"},
      {"calibrate --dir . --out ''", "pcsim: --out : no file named"},
      {"validate --json v.json --report v.json", "pcsim: --report v.json: is --json's file too; name two files"},
      // A folder no file can be made in, though root passes access() there.
      {"validate --json /proc/v.json", "pcsim: --json /proc/v.json: pcsim cannot write in the folder /proc"},
      {fmt::format("run '{}' --out /proc/pcsim-out", kTwoReaders), "pcsim: --out /proc/pcsim-out: pcsim cannot make a folder in /proc"},
  };
  for (const Case& c : cases) {
    const auto o = pcsim(c.args, dir);
    INFO(c.args << ": " << o.output);
    CHECK(o.status == 2);
    CHECK_THAT(o.output, Catch::Contains(c.message));
  }
  CHECK(names(dir) == std::set<std::string>{"adir", "dangling", "loop"});
  CHECK(names(dir / "adir").empty());
}

TEST_CASE("validate's options of the other mode are refused by name, not ignored", "[cli][outputs][validate]") {
  const fs::path dir = scratch("paths-validate-modes");
  const std::string kept = (fs::path(PCSIM_SOURCE_DIR) / "validation" / "here" / "dev-vm-2026-12-04").string();
  struct Case {
    std::string args;
    std::string message;
  };
  const std::vector<Case> cases = {
      {fmt::format("validate --from '{}' --json v.json --report r.html", kept),
       "pcsim: validate: --json, --report are options of the comparison with the paper's data, which --from does not make"},
      {fmt::format("validate --from '{}' --set hosts.0.memory=1GB", kept), "pcsim: validate: --set is an option of the comparison"},
      {"validate --here --dir . --switch large_folios=false", "pcsim: validate: --switch is an option of the comparison with the paper's data, "
                                                            "which --here does not make"},
      {fmt::format("validate --from '{}' --quick", kept), "pcsim: validate: --quick is an option of --here: --from scores the folder"},
      {"validate --out o --repeat 2", "pcsim: validate: --out, --repeat are options of --here"},
      {fmt::format("validate --here --from '{}'", kept), "pcsim: validate: --here runs the experiments, --from scores those kept"},
  };
  for (const Case& c : cases) {
    const auto o = pcsim(c.args, dir);
    INFO(c.args << ": " << o.output);
    CHECK(o.status == 2);
    CHECK_THAT(o.output, Catch::Contains(c.message));
  }
  CHECK(names(dir).empty());
}

TEST_CASE("an output never takes the place of the validation data or scenarios pcsim reads", "[cli][outputs][validate]") {
  const fs::path dir = scratch("paths-inputs");
  fs::copy(fs::path(PCSIM_SOURCE_DIR) / "validation" / "paper", dir / "data");
  const std::string scenarios = (fs::path(PCSIM_SOURCE_DIR) / "scenarios" / "paper").string();
  const std::string before = slurp(dir / "data" / "exp1_real_phase_times.csv");
  fs::create_symlink("data/exp1_real_phase_times.csv", dir / "link.csv");
  for (const std::string option : {"--json", "--report"}) {
    for (const std::string target : {"data/exp1_real_phase_times.csv", "link.csv"}) {
      const auto o = pcsim(fmt::format("validate --data data --scenarios '{}' {} {}", scenarios, option, target), dir);
      INFO(option << " " << target << ": " << o.output);
      CHECK(o.status == 2);
      CHECK_THAT(o.output, Catch::Contains(fmt::format("pcsim: {} {}: is ", option, target)) && Catch::Contains("which pcsim reads for this command"));
    }
  }
  CHECK(slurp(dir / "data" / "exp1_real_phase_times.csv") == before);
  CHECK(fs::is_symlink(dir / "link.csv"));
}

TEST_CASE("validation data that is a FIFO or a device is refused at once, not read for ever", "[cli][validate]") {
  const fs::path dir = scratch("paths-data-fifo");
  fs::copy(fs::path(PCSIM_SOURCE_DIR) / "validation" / "paper", dir / "data");
  const std::string scenarios = (fs::path(PCSIM_SOURCE_DIR) / "scenarios" / "paper").string();
  const fs::path file = dir / "data" / "exp1_real_phase_times.csv";
  fs::remove(file);
  REQUIRE(::mkfifo(file.c_str(), 0666) == 0);
  const auto fifo = pcsim(fmt::format("validate --data data --scenarios '{}' --report r.html", scenarios), dir);
  INFO(fifo.output);
  CHECK(fifo.status == 2);
  CHECK_THAT(fifo.output, Catch::Contains("exp1_real_phase_times.csv: not a regular file"));
  fs::remove(file);
  fs::create_symlink("/dev/zero", file);
  const auto zero = pcsim(fmt::format("validate --data data --scenarios '{}' --report r.html", scenarios), dir);
  INFO(zero.output);
  CHECK(zero.status == 2);
  CHECK_THAT(zero.output, Catch::Contains("exp1_real_phase_times.csv: not a regular file"));
  CHECK_FALSE(fs::exists(dir / "r.html"));
}

TEST_CASE("an output file in a folder pcsim may not write in is refused before any work", "[cli][outputs]") {
  if (::geteuid() == 0) {
    // root may write anywhere: the same refusal as a user without write permission, run as nobody.
    const fs::path dir = scratch("paths-readonly-root");
    fs::permissions(dir, fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec | fs::perms::others_read |
                             fs::perms::others_exec);
    // setpriv executes pcsim itself, so a clone in a folder only root may enter (CI's mktemp -d) works.
    const std::string command =
        fmt::format("setpriv --reuid=nobody --regid=nogroup --clear-groups '{}' validate --json '{}' --report '{}' 2>&1", PCSIM_BINARY,
                    (dir / "v.json").string(), (dir / "r.html").string());
    FILE* pipe = ::popen(command.c_str(), "r");
    REQUIRE(pipe != nullptr);
    std::string output;
    char buffer[4096];
    while (std::size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) output.append(buffer, n);
    const int raw = ::pclose(pipe);
    INFO(output);
    CHECK(WEXITSTATUS(raw) == 2);
    CHECK_THAT(output, Catch::Contains(fmt::format("--json {}: pcsim cannot write in the folder {}", (dir / "v.json").string(), dir.string())));
    CHECK_THAT(output, !Catch::Contains("exp1_20gb"));  // refused before validating
    CHECK(names(dir).empty());
  } else {
    const fs::path dir = scratch("paths-readonly");
    fs::permissions(dir, fs::perms::owner_read | fs::perms::owner_exec);
    const auto o = pcsim(fmt::format("validate --json '{}'", (dir / "v.json").string()));
    fs::permissions(dir, fs::perms::owner_all);
    INFO(o.output);
    CHECK(o.status == 2);
    CHECK_THAT(o.output, Catch::Contains("pcsim cannot write in the folder"));
  }
}

TEST_CASE("run --out takes a name at the file system's limit, and a refused one leaves no folder behind", "[cli][outputs]") {
  const fs::path dir = scratch("paths-long");
  const std::string longest(255, 'a');
  const auto ok = pcsim(fmt::format("run '{}' --out 'deep/er/{}' --quiet", kTwoReaders, longest), dir);
  INFO(ok.output);
  CHECK(ok.status == 0);
  CHECK(fs::exists(dir / "deep" / "er" / longest / "timeline.csv"));
  CHECK(leftovers(dir / "deep" / "er").empty());
  const auto refused = pcsim(fmt::format("run '{}' --out 'other/x/{}' --quiet", kTwoReaders, std::string(256, 'b')), dir);
  INFO(refused.output);
  CHECK(refused.status == 2);
  CHECK_THAT(refused.output, Catch::Contains("is a name longer than the file system allows"));
  CHECK_THAT(refused.output, !Catch::Contains("pcsim replaces only"));  // about the name, not what a folder holds
  CHECK_FALSE(fs::exists(dir / "other"));
}

TEST_CASE("pcsim killed by SIGTERM, SIGINT or SIGHUP at any moment leaves no staging folder, and its --out folder whole or absent",
          "[cli][outputs][signals]") {
  const fs::path dir = scratch("paths-signals");
  const std::string scenario = (fs::path(PCSIM_SOURCE_DIR) / "scenarios" / "paper" / "exp2.toml").string();
  int finished = 0, interrupted = 0;
  for (int i = 0; i < 40; ++i) {
    const int signal = std::array{SIGTERM, SIGINT, SIGHUP}[static_cast<std::size_t>(i % 3)];
    const fs::path out = dir / "out";
    // Signals blocked across fork, set to their defaults in the child before it takes them:
    // one arriving before exec must not run this test program's own (Catch2's) handlers.
    sigset_t block, previous;
    sigemptyset(&block);
    for (int s : {SIGTERM, SIGINT, SIGHUP}) sigaddset(&block, s);
    ::sigprocmask(SIG_BLOCK, &block, &previous);
    const pid_t child = ::fork();
    if (child == 0) {
      for (int s : {SIGTERM, SIGINT, SIGHUP}) ::signal(s, SIG_DFL);
      ::sigprocmask(SIG_SETMASK, &previous, nullptr);
      ::execl(PCSIM_BINARY, PCSIM_BINARY, "run", scenario.c_str(), "--set", "pipelines.count=32", "--set", "memory_sample_interval=0",
              "--trace", "--quiet", "--out", out.c_str(), static_cast<char*>(nullptr));
      ::_exit(127);
    }
    ::sigprocmask(SIG_SETMASK, &previous, nullptr);
    // Spread over the run, its writing included (about 0.1 s in a release build).
    std::this_thread::sleep_for(std::chrono::milliseconds(3 * i));
    ::kill(child, signal);
    int status = 0;
    REQUIRE(::waitpid(child, &status, 0) == child);
    INFO("signal " << signal << " after " << 3 * i << " ms");
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0) {
      ++finished;
    } else if (WIFEXITED(status)) {
      CHECK(WEXITSTATUS(status) == 128 + signal);
      ++interrupted;
    } else {
      CHECK(WIFSIGNALED(status));  // before pcsim's handler was installed: the default action
      ++interrupted;
    }
    const auto left = leftovers(dir);
    for (const auto& name : left) {
      std::string inside;
      if (fs::is_directory(dir / name)) {
        for (const auto& inner : names(dir / name)) inside += " " + inner;
      }
      INFO(name << " left behind, holding:" << inside);
      CHECK(name.empty());
    }
    for (const auto& name : left) fs::remove_all(dir / name);  // one leftover is reported once
    if (fs::exists(out)) {
      for (const char* file : {"timeline.csv", "memory.csv", "cache.csv", "summary.json", "timing.json", "report.html", "trace.json"}) {
        INFO(file);
        CHECK(fs::exists(out / file));
      }
      fs::remove_all(out);
    }
  }
  CHECK(finished + interrupted == 40);
}
