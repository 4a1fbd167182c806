// The rule for every file pcsim writes under a name the user gave (report/output_file.hpp): a
// regular file replaced whole, a link's regular target replaced and the link kept, a device or
// FIFO written through, pcsim's own descriptors written as they are, anything else refused
// naming the option; and what an interruption or a killed run leaves (interrupt_cleanup.hpp,
// OutputFolder's removal of abandoned staging folders).
#include "report/interrupt_cleanup.hpp"
#include "report/output_file.hpp"
#include "report/output_folder.hpp"
#include "report/output_rules.hpp"

#include "support/files.hpp"

#include <pagecache/error.hpp>

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <csignal>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

namespace fs = std::filesystem;
using pagecache::ConfigError;
using pagecache::report::OutputFile;
using pagecache::report::write_output_file;
using pagecache::testing::names;
using pagecache::testing::read_fifo;
using pagecache::testing::scratch;
using pagecache::testing::slurp;

namespace {

std::string message_of(const std::string& path, const std::string& option) {
  try {
    write_output_file(path, "{}\n", option);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(accepted)";
}

fs::file_type type_of(const fs::path& p) { return fs::symlink_status(p).type(); }


// A pid that no process has: a child that has exited and been reaped.
pid_t gone_pid() {
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  ::waitpid(child, nullptr, 0);
  return child;
}

}  // namespace

TEST_CASE("an output replaces a regular file whole, keeps its permissions, and leaves no temporary file", "[report][output-file]") {
  const fs::path dir = scratch("out-file-regular");
  std::ofstream(dir / "v.json") << "an older and longer content";
  fs::permissions(dir / "v.json", fs::perms::owner_read | fs::perms::owner_write);
  write_output_file((dir / "v.json").string(), "{}\n", "--json");
  CHECK(slurp(dir / "v.json") == "{}\n");
  CHECK((fs::status(dir / "v.json").permissions() & fs::perms::all) == (fs::perms::owner_read | fs::perms::owner_write));
  CHECK(names(dir) == std::set<std::string>{"v.json"});
  write_output_file((dir / "new.json").string(), "[]\n", "--json");
  CHECK(slurp(dir / "new.json") == "[]\n");
}

TEST_CASE("an output through a link to a regular file replaces that file and keeps the link", "[report][output-file]") {
  const fs::path dir = scratch("out-file-link");
  fs::create_directories(dir / "store");
  std::ofstream(dir / "store" / "results.json") << "old";
  fs::create_symlink(dir / "store" / "results.json", dir / "v.json");
  write_output_file((dir / "v.json").string(), "{}\n", "--json");
  CHECK(type_of(dir / "v.json") == fs::file_type::symlink);
  CHECK(slurp(dir / "store" / "results.json") == "{}\n");
  CHECK(names(dir / "store") == std::set<std::string>{"results.json"});
}

TEST_CASE("an output to a character device or a FIFO is written through, and stays what it was", "[report][output-file]") {
  const fs::path dir = scratch("out-file-devices");
  // A link to /dev/null as any user can make; as root, the device itself (mknod).
  fs::create_symlink("/dev/null", dir / "null-link");
  write_output_file((dir / "null-link").string(), "{}\n", "--json");
  CHECK(type_of(dir / "null-link") == fs::file_type::symlink);
  CHECK(fs::status("/dev/null").type() == fs::file_type::character);
  if (::geteuid() == 0) {
    REQUIRE(::mknod((dir / "mynull").c_str(), S_IFCHR | 0666, makedev(1, 3)) == 0);
    write_output_file((dir / "mynull").string(), "{}\n", "--json");
    CHECK(type_of(dir / "mynull") == fs::file_type::character);
  }
  REQUIRE(::mkfifo((dir / "fifo").c_str(), 0666) == 0);
  std::string received;
  std::thread reader([&] { received = read_fifo(dir / "fifo"); });
  write_output_file((dir / "fifo").string(), "through the pipe\n", "--csv");
  reader.join();
  CHECK(received == "through the pipe\n");
  CHECK(type_of(dir / "fifo") == fs::file_type::fifo);
  CHECK(names(dir).size() == (::geteuid() == 0 ? 3u : 2u));
}

TEST_CASE("an output to /proc/self/fd/N or /dev/fd/N is written on that descriptor, which stays open", "[report][output-file]") {
  int pipe[2];
  REQUIRE(::pipe(pipe) == 0);
  write_output_file(fmt::format("/proc/self/fd/{}", pipe[1]), "one ", "--json");
  write_output_file(fmt::format("/dev/fd/{}", pipe[1]), "two", "--json");
  REQUIRE(::fcntl(pipe[1], F_GETFD) != -1);  // still open: pcsim does not close what it did not open
  ::close(pipe[1]);
  char buffer[16] = {};
  const ssize_t n = ::read(pipe[0], buffer, sizeof buffer - 1);
  ::close(pipe[0]);
  CHECK(std::string(buffer, n > 0 ? static_cast<std::size_t>(n) : 0) == "one two");
  CHECK_THAT(message_of("/proc/self/fd/987", "--json"), Catch::Contains("--json /proc/self/fd/987: descriptor 987 is not open"));
}

TEST_CASE("an output refuses a folder, a link to nothing, a socket and a missing folder, naming the option, and touches nothing",
          "[report][output-file]") {
  const fs::path dir = scratch("out-file-refused");
  fs::create_directories(dir / "adir");
  std::ofstream(dir / "adir" / "keep.txt") << "mine";
  CHECK(message_of((dir / "adir").string(), "--report") == fmt::format("--report {}: is a folder; name a file", (dir / "adir").string()));
  CHECK(slurp(dir / "adir" / "keep.txt") == "mine");
  fs::create_symlink(dir / "nothing", dir / "dangling");
  CHECK_THAT(message_of((dir / "dangling").string(), "--csv"), Catch::Contains("--csv " + (dir / "dangling").string() + ": is a link to nothing"));
  CHECK_FALSE(fs::exists(dir / "nothing"));
  fs::create_symlink(dir / "adir", dir / "dir-link");
  CHECK_THAT(message_of((dir / "dir-link").string(), "--out"), Catch::Contains("is a folder"));
  CHECK_THAT(message_of((dir / "no" / "such" / "v.json").string(), "--json"),
             Catch::Contains(fmt::format("the folder {} does not exist", (dir / "no" / "such").string())));
  CHECK_FALSE(fs::exists(dir / "no"));
  const int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  const std::string socket_path = (dir / "sock").string();
  REQUIRE(socket_path.size() < sizeof address.sun_path);
  std::copy(socket_path.begin(), socket_path.end(), address.sun_path);
  REQUIRE(::bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0);
  CHECK_THAT(message_of(socket_path, "--json"), Catch::Contains("is a socket"));
  ::close(fd);
  CHECK(message_of("", "--json").find("no file named") != std::string::npos);
  CHECK(names(dir) == std::set<std::string>{"adir", "dangling", "dir-link", "sock"});
}

TEST_CASE("an output named at the file system's limit is written, and an uncommitted one leaves nothing", "[report][output-file]") {
  const fs::path dir = scratch("out-file-long");
  const std::string name(255, 'x');
  write_output_file((dir / name).string(), "long\n", "--json");
  CHECK(slurp(dir / name) == "long\n");
  {
    OutputFile file((dir / "half.csv").string(), "--csv");
    file.write("a,b\n");
  }  // not committed: an error on the way
  CHECK(names(dir) == std::set<std::string>{name});
}

TEST_CASE("an interrupted pcsim removes the temporary file and staging folder it was writing, and exits 128 + the signal",
          "[report][output-file][signals]") {
  for (int signal : {SIGINT, SIGTERM, SIGHUP}) {
    const fs::path dir = scratch(fmt::format("out-file-signal-{}", signal));
    std::ofstream(dir / "v.json") << "the previous results";
    const pid_t child = ::fork();
    if (child == 0) {
      pagecache::report::install_interrupt_cleanup();
      OutputFile file((dir / "v.json").string(), "--json");
      file.write("{\"half\": ");
      pagecache::report::OutputFolder folder((dir / "out").string());
      std::ofstream(folder.staging() / "timeline.csv") << "app,task\n";
      ::raise(signal);
      ::_exit(0);  // not reached: the handler exits
    }
    int status = 0;
    REQUIRE(::waitpid(child, &status, 0) == child);
    REQUIRE(WIFEXITED(status));
    CHECK(WEXITSTATUS(status) == 128 + signal);
    CHECK(names(dir) == std::set<std::string>{"v.json"});  // no temporary file, no staging folder
    CHECK(slurp(dir / "v.json") == "the previous results");
  }
}

TEST_CASE("a staging folder a killed run left is removed by the next run into its folder, and nothing else is",
          "[report][output-folder][signals]") {
  const fs::path dir = scratch("out-folder-abandoned");
  unsigned serial = 0;
  auto staging = [&](const std::string& name, pid_t pid, const std::string& marker) {
    const fs::path p = dir / fmt::format("{}-{}-{:08x}", name, pid, 0x0123abc0 + serial++);
    fs::create_directories(p);
    if (!marker.empty()) std::ofstream(p / pagecache::report::kMarkerName) << marker;
    std::ofstream(p / "timeline.csv") << "app,task\n";
    return p;
  };
  const pid_t gone = gone_pid();
  const fs::path abandoned = staging(".pcsim.tmp", gone, pagecache::report::kMarkerText);
  std::ofstream(abandoned / fmt::format(".pcsim.tmp-{}-89abcdef", gone)) << "half a csv";
  const fs::path older_name = staging(".keep.tmp", gone, pagecache::report::kMarkerText);  // an earlier version's name
  const fs::path alive = staging(".pcsim.tmp", ::getpid(), pagecache::report::kMarkerText);
  const fs::path no_marker = staging(".pcsim.tmp", gone, "");
  const fs::path other_marker = staging(".x.tmp", gone, "not pcsim's text\n");
  const fs::path foreign = staging(".y.tmp", gone, pagecache::report::kMarkerText);
  std::ofstream(foreign / "notes.txt") << "someone's";
  std::ofstream(dir / fmt::format(".z.tmp-{}-0123abcd", gone)) << "a file, not a folder";
  // Near misses of the name: not pcsim's staging folders, whatever they hold.
  std::vector<fs::path> near_misses;
  for (const std::string& name : {fmt::format(".pcsim.tmp-{}-0123ABCD", gone), fmt::format(".pcsim.tmp-{}-0123abc", gone),
                                  std::string(".pcsim.tmp--0123abcd"), fmt::format("pcsim.tmp-{}-0123abcd", gone),
                                  fmt::format(".pcsim.tmp-{}x-0123abcd", gone), fmt::format(".tmp-{}-0123abcd", gone)}) {
    near_misses.push_back(dir / name);
    fs::create_directories(near_misses.back());
    std::ofstream(near_misses.back() / pagecache::report::kMarkerName) << pagecache::report::kMarkerText;
    std::ofstream(near_misses.back() / "timeline.csv") << "app,task\n";
  }
  {
    pagecache::report::OutputFolder folder((dir / "out").string());
    folder.commit();
  }
  CHECK_FALSE(fs::exists(abandoned));
  CHECK_FALSE(fs::exists(older_name));
  for (const fs::path& kept : {alive, no_marker, other_marker, foreign}) {
    INFO(kept.string());
    CHECK(fs::exists(kept / "timeline.csv"));
  }
  CHECK(fs::exists(foreign / "notes.txt"));
  for (const fs::path& kept : near_misses) {
    INFO(kept.string());
    CHECK(fs::exists(kept / "timeline.csv"));
  }
  CHECK(fs::exists(dir / fmt::format(".z.tmp-{}-0123abcd", gone)));
  CHECK(fs::exists(dir / "out" / pagecache::report::kMarkerName));
}

TEST_CASE("an output folder whose run fails leaves none of the folders made above it", "[report][output-folder]") {
  const fs::path dir = scratch("out-folder-parents");
  { pagecache::report::OutputFolder folder((dir / "a" / "b" / "out").string()); }  // never committed
  CHECK(names(dir).empty());
  fs::create_directories(dir / "a");
  std::ofstream(dir / "a" / "mine.txt") << "mine";
  { pagecache::report::OutputFolder folder((dir / "a" / "b" / "c" / "out").string()); }
  CHECK(names(dir / "a") == std::set<std::string>{"mine.txt"});
}
