#pragma once
// Running a program as a test's child: its output, exit status, wall time and peak memory,
// killed if it runs past a deadline, so that a test of a hang or a memory blow-up ends and
// says so instead of hanging the suite.

#include <chrono>
#include <csignal>
#include <cstdio>
#include <fcntl.h>
#include <string>
#include <sys/resource.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

namespace pagecache::testing {

struct ChildResult {
  int status = -1;  ///< exit status; -1 if killed by a signal
  bool timed_out = false;
  double seconds = 0.0;
  long max_rss_kb = 0;  ///< peak resident memory
  std::string output;   ///< stdout and stderr
};

/// Runs `argv` (argv[0] a path) in `cwd` (if not empty) with stdin from /dev/null, killing it
/// after `deadline_s` seconds; with `address_space` (bytes), allocations beyond it fail.
inline ChildResult run_child(const std::vector<std::string>& argv, double deadline_s, const std::string& cwd = {},
                             rlim_t address_space = RLIM_INFINITY) {
  int out[2];
  if (::pipe(out) != 0) return {};
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::dup2(out[1], 1);
    ::dup2(out[1], 2);
    ::close(out[0]);
    ::close(out[1]);
    const int null = ::open("/dev/null", O_RDONLY);
    ::dup2(null, 0);
    if (!cwd.empty() && ::chdir(cwd.c_str()) != 0) ::_exit(126);
    const rlimit limit{address_space, address_space};
    if (address_space != RLIM_INFINITY && ::setrlimit(RLIMIT_AS, &limit) != 0) ::_exit(126);
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    ::execv(args[0], args.data());
    ::_exit(127);
  }
  ::close(out[1]);
  ::fcntl(out[0], F_SETFL, O_NONBLOCK);
  ChildResult r;
  int raw = 0;
  rusage usage{};
  char buffer[4096];
  for (;;) {
    for (ssize_t n; (n = ::read(out[0], buffer, sizeof buffer)) > 0;) r.output.append(buffer, static_cast<std::size_t>(n));
    const pid_t done = ::wait4(pid, &raw, WNOHANG, &usage);
    if (done == pid) break;
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > deadline_s && !r.timed_out) {
      r.timed_out = true;
      ::kill(pid, SIGKILL);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  for (ssize_t n; (n = ::read(out[0], buffer, sizeof buffer)) > 0;) r.output.append(buffer, static_cast<std::size_t>(n));
  ::close(out[0]);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.max_rss_kb = usage.ru_maxrss;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return r;
}

}  // namespace pagecache::testing
