#include "sweep/results_file.hpp"

#include "sweep/result_line.hpp"

#include <pagecache/error.hpp>

#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

namespace pagecache::sweep {

namespace {

// A results file pcsim made is a regular file of one name. A link, or a second name, points
// at bytes someone else keeps (another sweep's folder, a backup made with cp -l): pcsim reads
// and changes neither.
void refuse_unless_made_by_pcsim(const std::string& path, const struct stat& st) {
  const char* why = nullptr;
  if (S_ISLNK(st.st_mode)) why = "is a symbolic link";
  else if (S_ISDIR(st.st_mode)) why = "is a folder";
  else if (!S_ISREG(st.st_mode)) why = "is not a regular file (a device, FIFO or socket)";
  if (why != nullptr) throw ConfigError(fmt::format("{}: {}, not a results file pcsim made: left as it is", path, why));
  if (st.st_nlink > 1) {
    throw ConfigError(fmt::format("{}: has {} hard links: its bytes are another file's too, which pcsim would change; left as it is", path,
                                  st.st_nlink));
  }
}

[[noreturn]] void cannot_open(const std::string& path, int error) {
  if (error == ELOOP) throw ConfigError(fmt::format("{}: is a symbolic link, not a results file pcsim made: left as it is", path));
  if (error == EISDIR) throw ConfigError(fmt::format("{}: is a folder, not a results file pcsim made: left as it is", path));
  throw Error(fmt::format("{}: cannot open: {}", path, std::strerror(error)));
}

// The file's bytes, read from its descriptor to its end.
std::string read_all(int fd, const std::string& path) {
  std::string text;
  char buffer[1 << 16];
  for (off_t at = 0;;) {
    const ssize_t n = ::pread(fd, buffer, sizeof buffer, at);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw Error(fmt::format("{}: cannot read: {}", path, std::strerror(errno)));
    if (n == 0) return text;
    text.append(buffer, static_cast<std::size_t>(n));
    at += n;
  }
}

}  // namespace

ResultsText read_results_text(std::string_view text, std::string_view fingerprint, const std::string& name) {
  ResultsText out;
  std::size_t number = 0;
  std::size_t at = 0;
  for (; at < text.size();) {
    const std::size_t end = text.find('\n', at);
    ++number;
    if (end == std::string_view::npos) break;
    const std::string_view line = text.substr(at, end - at);
    LineCheck check = check_result_line(line, fingerprint);
    if (!check.problem.empty()) throw ConfigError(fmt::format("{}:{}: {}; left as it is", name, number, check.problem));
    out.lines.push_back({std::move(check.id), number, line});
    at = end + 1;
  }
  out.whole = at;
  if (at < text.size()) {
    // A shard killed while it wrote its last line left it without its newline: that run is run
    // again. Anything else there was not written by pcsim.
    const LineCheck cut = check_cut_result_line(text.substr(at), fingerprint);
    if (!cut.problem.empty()) {
      throw ConfigError(fmt::format("{}:{}: a last line without its newline, {}; left as it is", name, number, cut.problem));
    }
  }
  return out;
}

std::string read_results_file(const std::string& path) {
  // O_NOFOLLOW: a link is refused, not followed; O_NONBLOCK: a FIFO does not hang the open.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
  if (fd < 0) cannot_open(path, errno);
  struct stat st {};
  try {
    if (::fstat(fd, &st) != 0) throw Error(fmt::format("{}: cannot read: {}", path, std::strerror(errno)));
    refuse_unless_made_by_pcsim(path, st);
    std::string text = read_all(fd, path);
    ::close(fd);
    return text;
  } catch (...) {
    ::close(fd);
    throw;
  }
}

ResultsFile::ResultsFile(const std::string& path, const std::string& fingerprint) : path_(path) {
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_APPEND | O_NOFOLLOW | O_NONBLOCK | O_NOCTTY | O_CLOEXEC, 0644);
  if (fd_ < 0) cannot_open(path, errno);
  try {
    struct stat st {};
    if (::fstat(fd_, &st) != 0) throw Error(fmt::format("{}: cannot read: {}", path, std::strerror(errno)));
    refuse_unless_made_by_pcsim(path, st);
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) throw ConfigError(fmt::format("{}: another pcsim is writing these results (the same shard twice?)", path));
    const std::string text = read_all(fd_, path);
    const ResultsText results = read_results_text(text, fingerprint, path);  // throws before any change
    if (results.whole < text.size() && ::ftruncate(fd_, static_cast<off_t>(results.whole)) != 0) {
      throw Error(fmt::format("{}: cannot drop its partial last line: {}", path, std::strerror(errno)));
    }
    for (const ResultsText::Line& line : results.lines) done_.insert(line.id);
  } catch (...) {
    ::close(fd_);
    throw;
  }
}

ResultsFile::~ResultsFile() {
  if (fd_ >= 0) ::close(fd_);  // the lock goes with it
}

void ResultsFile::append(const std::string& line) {
  const std::string whole = line + "\n";
  std::string_view rest = whole;
  while (!rest.empty()) {
    const ssize_t n = ::write(fd_, rest.data(), rest.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw Error(fmt::format("{}: cannot write: {}", path_, std::strerror(errno)));
    rest.remove_prefix(static_cast<std::size_t>(n));
  }
}

}  // namespace pagecache::sweep
