#include "sweep/results_file.hpp"

#include <pagecache/error.hpp>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <string_view>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

namespace pagecache::sweep {

std::string result_id(const std::string& line) {
  const nlohmann::json doc = nlohmann::json::parse(line, nullptr, false);
  if (!doc.is_object() || !doc.contains("id") || !doc["id"].is_string()) return {};
  return doc["id"].get<std::string>();
}

ResultsFile::ResultsFile(const std::string& path) : path_(path) {
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (fd_ < 0) throw Error(fmt::format("{}: cannot open: {}", path, std::strerror(errno)));
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    ::close(fd_);
    throw ConfigError(fmt::format("{}: another pcsim is writing these results (the same shard twice?)", path));
  }
  struct stat st {};
  ::fstat(fd_, &st);
  std::string text(static_cast<std::size_t>(st.st_size), '\0');
  for (std::size_t got = 0; got < text.size();) {
    const ssize_t n = ::pread(fd_, text.data() + got, text.size() - got, static_cast<off_t>(got));
    if (n <= 0) throw Error(fmt::format("{}: cannot read: {}", path, std::strerror(errno)));
    got += static_cast<std::size_t>(n);
  }
  // A run killed mid-line left no newline after it: that run is run again.
  const std::size_t whole = text.rfind('\n') == std::string::npos ? 0 : text.rfind('\n') + 1;
  if (whole < text.size() && ::ftruncate(fd_, static_cast<off_t>(whole)) != 0) {
    throw Error(fmt::format("{}: cannot drop its partial last line: {}", path, std::strerror(errno)));
  }
  std::size_t line_no = 0;
  for (std::size_t at = 0; at < whole;) {
    const std::size_t end = text.find('\n', at);
    ++line_no;
    const std::string line = text.substr(at, end - at);
    at = end + 1;
    const std::string id = result_id(line);
    if (id.empty()) throw ConfigError(fmt::format("{}:{}: not a result pcsim wrote", path, line_no));
    done_.insert(id);
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
