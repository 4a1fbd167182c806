#pragma once
// SystemInfo: what `pcsim calibrate` reads of the machine rather than measures: the CPU, the
// memory, the kernel's writeback settings, transparent huge pages, the file system of the
// folder it measures in, and whether it runs as root or in a virtual machine.

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace pagecache::calibrate {

struct SystemInfo {
  std::string hostname;
  std::string kernel;     ///< uname -r
  std::string cpu_model;  ///< /proc/cpuinfo "model name" (empty if none)
  int cores = 1;          ///< processors online
  bool hypervisor = false;  ///< the CPU says it runs under one (/proc/cpuinfo flag)
  bool root = false;
  std::int64_t memory_total = 0;      ///< /proc/meminfo MemTotal, bytes
  std::int64_t memory_available = 0;  ///< MemAvailable
  std::int64_t memory_free = 0;       ///< MemFree
  std::int64_t page_size = 4096;
  std::int64_t min_free = 0;  ///< /proc/sys/vm/min_free_kbytes, bytes: the kernel's watermarks follow it
  std::string transparent_hugepages;  ///< the selected mode: always, madvise, never (empty: absent)
  // /proc/sys/vm: a ratio is 0 when its _bytes setting is used instead.
  double dirty_ratio = 0.2;
  double dirty_background_ratio = 0.1;
  std::int64_t dirty_bytes = 0;
  std::int64_t dirty_background_bytes = 0;
  double dirty_expire = 30.0;        ///< seconds (dirty_expire_centisecs)
  double writeback_interval = 5.0;   ///< seconds (dirty_writeback_centisecs)
  std::string file_system;           ///< of the folder measured in (statfs type, e.g. ext4)
  std::int64_t file_system_free = 0; ///< bytes an ordinary user may still write there
  bool memory_limited = false;       ///< this process is in a memory cgroup with a limit
};

/// /proc/meminfo now.
std::string read_meminfo();

/// Reads it now, for measurements in `dir`.
SystemInfo read_system_info(const std::filesystem::path& dir);

// The parsers, apart for tests.
/// A /proc/meminfo field in bytes ("MemTotal:  24633100 kB" -> 25224294400); -1 if absent.
std::int64_t meminfo_bytes(std::string_view meminfo, std::string_view key);
/// The bracketed word of a sysfs choice ("always [madvise] never" -> "madvise").
std::string selected_choice(std::string_view text);
/// The first "model name" of /proc/cpuinfo, and whether its flags name a hypervisor.
std::string cpuinfo_model(std::string_view cpuinfo);
bool cpuinfo_hypervisor(std::string_view cpuinfo);

}  // namespace pagecache::calibrate
