#include "calibrate/device_limits.hpp"

#include <fmt/format.h>

#include <fstream>
#include <string>
#include <system_error>

#include <sys/stat.h>
#include <sys/sysmacros.h>

namespace pagecache::calibrate {

namespace {

namespace fs = std::filesystem;

// A sysfs number of KiB, in bytes; -1 if absent or not a number.
std::int64_t kib_file(const fs::path& path) {
  std::ifstream in(path);
  std::int64_t kib = -1;
  return in >> kib && kib >= 0 ? kib * 1024 : -1;
}

std::string first_word(const fs::path& path) {
  std::ifstream in(path);
  std::string word;
  in >> word;
  return word;
}

}  // namespace

DeviceLimits read_device_limits(const fs::path& sys, unsigned major, unsigned minor) {
  DeviceLimits d;
  const std::string number = fmt::format("{}:{}", major, minor);
  std::error_code ec;
  // A block device: its queue is the disk's (a partition's parent holds it), and so is its bdi.
  fs::path queue;
  std::string bdi = number;
  const fs::path block = sys / "dev" / "block" / number;
  if (fs::exists(block, ec)) {
    fs::path disk = fs::canonical(block, ec);
    queue = block / "queue";
    if (!ec && fs::exists(disk / "partition", ec)) {
      disk = disk.parent_path();
      queue = block / ".." / "queue";  // the kernel resolves a link before its ".."
      if (const std::string parent = first_word(disk / "dev"); !parent.empty()) bdi = parent;
    }
    d.device = disk.filename().string();
  }
  const fs::path bdi_read_ahead = sys / "class" / "bdi" / bdi / "read_ahead_kb";
  if ((d.read_ahead = kib_file(bdi_read_ahead)) >= 0) {
    d.read_ahead_from = bdi_read_ahead.string();
  } else if (!queue.empty() && (d.read_ahead = kib_file(queue / "read_ahead_kb")) >= 0) {
    d.read_ahead_from = (queue / "read_ahead_kb").string();
  } else {
    d.read_ahead_from = fmt::format("neither {} nor a block device's queue/read_ahead_kb for device {} (a file system whose readahead "
                                    "sysfs does not show, e.g. btrfs or overlayfs)",
                                    bdi_read_ahead.string(), number);
  }
  if (!queue.empty() && (d.max_request = kib_file(queue / "max_sectors_kb")) >= 0) {
    d.max_request_from = (queue / "max_sectors_kb").string();
  } else if (queue.empty()) {
    d.max_request_from = fmt::format("device {} is not a block device ({} does not exist: NFS, FUSE, btrfs, overlayfs...): the largest request "
                                     "is not the kernel's to say",
                                     number, block.string());
  } else {
    d.max_request_from = fmt::format("no {}", (queue / "max_sectors_kb").string());
  }
  return d;
}

DeviceLimits device_limits_of(const fs::path& dir) {
  struct stat st{};
  if (::stat(dir.c_str(), &st) != 0) {
    DeviceLimits d;
    d.read_ahead_from = d.max_request_from = fmt::format("cannot stat '{}'", dir.string());
    return d;
  }
  return read_device_limits("/sys", ::major(st.st_dev), ::minor(st.st_dev));
}

}  // namespace pagecache::calibrate
