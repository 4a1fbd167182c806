#include "calibrate/memory_cgroup.hpp"

#include "calibrate/system_info.hpp"

#include <pagecache/error.hpp>

#include <fmt/format.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>
#include <thread>

#include <sys/stat.h>
#include <unistd.h>

namespace pagecache::calibrate {

namespace {

namespace fs = std::filesystem;

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The cgroup v2 group whose children may have a memory controller: this process's own, if it
// offers "memory" in its cgroup.subtree_control. Empty if none.
fs::path v2_parent() {
  const std::string group = own_cgroup("::");
  if (group.empty()) return {};
  for (const char* root : {"/sys/fs/cgroup/unified", "/sys/fs/cgroup"}) {
    const fs::path mount(root);
    std::error_code ec;
    if (!fs::exists(mount / "cgroup.controllers", ec)) continue;
    const fs::path parent = mount / group.substr(1);
    std::istringstream control(read_text(parent / "cgroup.subtree_control"));
    for (std::string word; control >> word;)
      if (word == "memory") return parent;
    return {};
  }
  return {};
}

fs::path v1_parent() {
  const std::string group = own_cgroup(":memory:");
  if (group.empty()) return {};
  return fs::path("/sys/fs/cgroup/memory") / group.substr(1);
}

// Writes `text` to a control file; the errno's text if it could not.
std::string write_control(const fs::path& path, const std::string& text) {
  errno = 0;
  std::ofstream out(path);
  if (out) out << text << std::flush;
  if (out) return {};
  return std::strerror(errno != 0 ? errno : EIO);
}

}  // namespace

MemoryCgroup::MemoryCgroup(std::int64_t max_bytes) {
  static std::atomic<int> made{0};
  const std::string name = fmt::format("pcsim-fio-{}-{}", ::getpid(), ++made);
  fs::path parent = v2_parent();
  v2_ = !parent.empty();
  if (!v2_) parent = v1_parent();
  const char* const needs = "validate --here --fio --memory-max needs a memory cgroup this user may make";
  if (parent.empty()) throw Error(fmt::format("{}: no cgroup v2 group offering the memory controller and no cgroup v1 memory hierarchy in /proc/self/cgroup", needs));
  dir_ = parent / name;
  if (::mkdir(dir_.c_str(), 0755) != 0) throw Error(fmt::format("{}: cannot make {} ({})", needs, dir_.string(), std::strerror(errno)));
  const fs::path limit = dir_ / (v2_ ? "memory.max" : "memory.limit_in_bytes");
  if (const std::string why = write_control(limit, std::to_string(max_bytes)); !why.empty()) {
    ::rmdir(dir_.c_str());
    throw Error(fmt::format("{}: cannot write {} to {} ({})", needs, max_bytes, limit.string(), why));
  }
}

MemoryCgroup::~MemoryCgroup() {
  // A task that has just exited may hold the group for a moment (EBUSY): two seconds at most.
  for (int attempt = 0; attempt < 100; ++attempt) {
    if (::rmdir(dir_.c_str()) == 0 || errno != EBUSY) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

std::int64_t MemoryCgroup::peak() const {
  const std::string text = read_text(dir_ / (v2_ ? "memory.peak" : "memory.max_usage_in_bytes"));
  try {
    return text.empty() ? -1 : std::stoll(text);
  } catch (const std::exception&) {
    return -1;
  }
}

}  // namespace pagecache::calibrate
