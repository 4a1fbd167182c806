#pragma once
// run_watched: runs a function in a forked child process, which this process watches: the
// child's answer (a string, empty meaning success) comes back through a pipe; a crash,
// sanitizer report or exception ends only the child; a child that holds more resident memory
// than a bound, or runs longer than a bound, is killed. For tests replaying inputs that once
// asked the code for unbounded memory: they must fail, not take the machine's memory.
//
// Why not setrlimit(RLIMIT_AS) in the child: under AddressSanitizer the process has already
// reserved terabytes of address space for shadow memory, so any address-space limit either
// stops nothing or stops everything.

#include <poll.h>
#include <signal.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <cstring>
#include <exception>
#include <fstream>
#include <functional>
#include <string>
#include <typeinfo>

namespace pagecache::testing {

struct WatchLimits {
  /// Resident memory the child may take beyond what it started with (this process's).
  std::int64_t resident_bytes = std::int64_t{512} << 20;
  int seconds = 30;
};

inline std::int64_t resident_pages(const std::string& statm) {
  std::int64_t size = 0;
  std::int64_t resident = 0;
  std::ifstream(statm) >> size >> resident;
  return resident;
}

/// "" if the function returned "" in the child; else its answer, or why the child failed.
inline std::string run_watched(const std::function<std::string()>& function, WatchLimits limits = {}) {
  const std::int64_t page = sysconf(_SC_PAGESIZE);
  const std::int64_t start_pages = resident_pages("/proc/self/statm");
  int fds[2];
  if (pipe(fds) != 0) return std::string("pipe: ") + std::strerror(errno);
  const pid_t pid = fork();
  if (pid < 0) return std::string("fork: ") + std::strerror(errno);
  if (pid == 0) {
    close(fds[0]);
    std::string answer;
    try {
      answer = function();
    } catch (const std::exception& e) {
      answer = std::string("unexpected exception ") + typeid(e).name() + ": " + e.what();
    } catch (...) {
      answer = "unexpected exception of a type not derived from std::exception";
    }
    for (std::size_t done = 0; done < answer.size();) {
      const ssize_t n = write(fds[1], answer.data() + done, answer.size() - done);
      if (n <= 0) break;
      done += static_cast<std::size_t>(n);
    }
    _exit(0);  // no exit handlers, no leak check of the parent's copied state
  }
  close(fds[1]);
  const auto start = std::chrono::steady_clock::now();
  const std::string statm = "/proc/" + std::to_string(pid) + "/statm";
  std::string answer;
  std::string killed;
  bool pipe_open = true;
  int status = 0;
  for (;;) {
    if (pipe_open) {
      pollfd p{fds[0], POLLIN, 0};
      if (poll(&p, 1, 10) > 0) {
        char buffer[4096];
        const ssize_t n = read(fds[0], buffer, sizeof buffer);
        if (n > 0) answer.append(buffer, static_cast<std::size_t>(n));
        else pipe_open = false;
      }
    } else {
      usleep(10'000);
    }
    if (waitpid(pid, &status, WNOHANG) == pid) break;
    const std::int64_t grown = (resident_pages(statm) - start_pages) * page;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (killed.empty() && grown > limits.resident_bytes) {
      killed = "killed: grew by more than " + std::to_string(limits.resident_bytes >> 20) + " MiB of resident memory";
    } else if (killed.empty() && elapsed > limits.seconds) {
      killed = "killed: still running after " + std::to_string(limits.seconds) + " s";
    }
    if (!killed.empty()) kill(pid, SIGKILL);
  }
  for (char buffer[4096]; pipe_open;) {
    const ssize_t n = read(fds[0], buffer, sizeof buffer);
    if (n > 0) answer.append(buffer, static_cast<std::size_t>(n));
    else pipe_open = false;
  }
  close(fds[0]);
  if (!killed.empty()) return killed;
  if (WIFSIGNALED(status)) return "crashed: signal " + std::to_string(WTERMSIG(status)) + " (its report is above)";
  if (WIFEXITED(status) && WEXITSTATUS(status) != 0) {
    return "crashed: exit status " + std::to_string(WEXITSTATUS(status)) + " (its report is above)";
  }
  return answer;
}

}  // namespace pagecache::testing
