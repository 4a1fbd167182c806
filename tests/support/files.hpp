#pragma once
// Files for tests: fresh scratch folders, a file's contents, a folder's entries.

#include <fmt/format.h>

#include <fcntl.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <unistd.h>

namespace pagecache::testing {

/// A fresh, empty scratch folder per test (and per process, for ctest -j).
inline std::filesystem::path scratch(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / fmt::format("pcsim-test-{}-{}", ::getpid(), name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

inline std::string slurp(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The names in `dir`, in order.
inline std::set<std::string> names(const std::filesystem::path& dir) {
  std::set<std::string> out;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) out.insert(entry.path().filename().string());
  return out;
}

/// A FIFO's bytes until its writers close it, read with system calls only: a thread blocked in
/// the C library's fopen() would hold its stream list lock, which the child of a concurrent
/// popen() waits for.
inline std::string read_fifo(const std::filesystem::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  std::string out;
  char buffer[4096];
  for (ssize_t n; fd >= 0 && (n = ::read(fd, buffer, sizeof buffer)) > 0;) out.append(buffer, static_cast<std::size_t>(n));
  if (fd >= 0) ::close(fd);
  return out;
}

}  // namespace pagecache::testing
