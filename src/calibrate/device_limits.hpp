#pragma once
// The kernel's limits on requests to the device under a folder, read from sysfs, not measured:
// its readahead window (the bdi's read_ahead_kb, which network file systems have too) and the
// largest request the block layer sends it (the queue's max_sectors_kb; block devices only).

#include <cstdint>
#include <filesystem>
#include <string>

namespace pagecache::calibrate {

struct DeviceLimits {
  std::string device;             ///< the block device's name (the disk's, for a partition); empty if none
  std::int64_t read_ahead = -1;   ///< bytes; -1: not known
  std::int64_t max_request = -1;  ///< bytes; -1: not known
  std::string read_ahead_from;    ///< the file read, or why it is not known
  std::string max_request_from;
};

/// For the device numbered major:minor (a stat's st_dev), under the sysfs root `sys`.
DeviceLimits read_device_limits(const std::filesystem::path& sys, unsigned major, unsigned minor);

/// For the file system holding `dir`, from /sys.
DeviceLimits device_limits_of(const std::filesystem::path& dir);

}  // namespace pagecache::calibrate
