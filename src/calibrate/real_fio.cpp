#include "calibrate/real_fio.hpp"

#include "calibrate/cold_start.hpp"
#include "calibrate/measure.hpp"
#include "calibrate/memory_cgroup.hpp"
#include "calibrate/scratch.hpp"
#include "calibrate/system_info.hpp"

#include <pagecache/error.hpp>

#include <fmt/format.h>

#include <array>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <vector>

#include <fcntl.h>
#include <poll.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace pagecache::calibrate {

namespace {

using Clock = std::chrono::steady_clock;

// A pipe whose ends close with it.
struct Pipe {
  int fd[2] = {-1, -1};
  Pipe() {
    if (::pipe2(fd, O_CLOEXEC) != 0) throw Error(fmt::format("fio: cannot make a pipe ({})", std::strerror(errno)));
  }
  ~Pipe() {
    for (int f : fd)
      if (f >= 0) ::close(f);
  }
  void close_end(int i) {
    ::close(fd[i]);
    fd[i] = -1;
  }
};

// The child's output: stdout and stderr read until both close, or `deadline` passes (then
// false: still running), or (if `stoppable`) a stop is requested.
bool drain(int out_fd, int err_fd, std::string& out, std::string& err, Clock::time_point deadline, bool stoppable = true) {
  std::array<pollfd, 2> fds{pollfd{out_fd, POLLIN, 0}, pollfd{err_fd, POLLIN, 0}};
  std::array<std::string*, 2> into{&out, &err};
  int open = 2;
  std::array<char, 65536> buffer{};
  while (open > 0) {
    if (Clock::now() > deadline || (stoppable && stop_requested())) return false;
    if (::poll(fds.data(), fds.size(), 200) < 0 && errno != EINTR) return false;
    for (std::size_t i = 0; i < fds.size(); ++i) {
      if (fds[i].fd < 0 || fds[i].revents == 0) continue;
      const ssize_t n = ::read(fds[i].fd, buffer.data(), buffer.size());
      if (n > 0) {
        into[i]->append(buffer.data(), static_cast<std::size_t>(n));
      } else if (n == 0 || errno != EINTR) {
        fds[i].fd = -1;  // poll skips it
        --open;
      }
    }
  }
  return true;
}

// The last `n` bytes of fio's stderr, for a message.
std::string tail(const std::string& text, std::size_t n = 2000) {
  const std::string t = text.size() > n ? "..." + text.substr(text.size() - n) : text;
  return t.empty() ? "(nothing on stderr)" : t;
}

std::string first_json_line_on(const std::string& out) {
  for (std::size_t at = 0; at < out.size();) {
    if (out[at] == '{') return out.substr(at);
    const auto next = out.find('\n', at);
    if (next == std::string::npos) break;
    at = next + 1;
  }
  return {};
}

}  // namespace

RealFio run_real_fio(const std::filesystem::path& job, const std::filesystem::path& dir, int timeout_seconds, double settle_limit,
                     const std::string& fio, const MemoryCgroup* cgroup) {
  const Scratch scratch(dir, "pcsim-fio");
  RealFio run;
  run.dropped_all_caches = ::geteuid() == 0 && drop_all_caches();
  if (reported_free_bytes() >= 0) run.reporting_settled = wait_for_reporting(settle_limit) ? 1 : 0;
  const std::string job_path = std::filesystem::absolute(job).string();
  std::vector<std::string> args{fio, "--output-format=json", fmt::format("--timeout={}", timeout_seconds), job_path};
  // posix_spawn cannot place its child in a cgroup: a shell joins it, then becomes fio.
  if (cgroup != nullptr) args.insert(args.begin(), {"/bin/sh", "-c", R"(echo $$ > "$0" && exec "$@")", cgroup->procs().string()});
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);

  Pipe out, err;
  posix_spawn_file_actions_t actions;
  ::posix_spawn_file_actions_init(&actions);
  ::posix_spawn_file_actions_adddup2(&actions, out.fd[1], STDOUT_FILENO);
  ::posix_spawn_file_actions_adddup2(&actions, err.fd[1], STDERR_FILENO);
  ::posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  ::posix_spawn_file_actions_addchdir_np(&actions, scratch.file("").c_str());
  pid_t pid = 0;
  const auto start = Clock::now();
  const int spawned = ::posix_spawnp(&pid, args.front().c_str(), &actions, nullptr, argv.data(), environ);
  ::posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) throw Error(fmt::format("cannot start {} ({}): is fio installed (scripts/install-deps)?", fio, std::strerror(spawned)));
  out.close_end(1);
  err.close_end(1);

  std::string errors;
  // fio's own --timeout ends it; a minute more for its files and report.
  const bool ended = drain(out.fd[0], err.fd[0], run.json, errors, start + std::chrono::seconds(timeout_seconds + 60));
  if (!ended) {
    // fio's job processes are sessions of their own: a SIGINT lets fio stop them, a SIGKILL
    // (if it has not ended within seconds) would leave them running.
    ::kill(pid, SIGINT);
    if (!drain(out.fd[0], err.fd[0], run.json, errors, Clock::now() + std::chrono::seconds(20), false)) ::kill(pid, SIGKILL);
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  run.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  if (cgroup != nullptr) run.peak_memory = cgroup->peak();
  const std::string what = fmt::format("fio {}", job.string());
  if (stop_requested()) throw Error(fmt::format("{}: interrupted: fio stopped, its files removed", what));
  if (!ended) throw Error(fmt::format("{}: still running {} s after its --timeout of {} s: killed, its files removed", what, 60, timeout_seconds));
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    const std::string how = WIFEXITED(status) ? fmt::format("exit status {}", WEXITSTATUS(status)) : fmt::format("signal {}", WTERMSIG(status));
    throw Error(fmt::format("{} failed ({}): {}", what, how, tail(errors)));
  }
  run.json = first_json_line_on(run.json);
  if (run.json.empty()) throw Error(fmt::format("{}: no JSON report on its stdout: {}", what, tail(errors)));
  return run;
}

}  // namespace pagecache::calibrate
