#pragma once
// SystemInfo: what `pcsim calibrate` reads of the machine rather than measures: the CPU, the
// memory, the kernel's writeback settings, transparent huge pages, the file system of the
// folder it measures in, whether it runs as root or in a virtual machine, and what else on the
// machine may change the measurements: other load on the CPUs, a hypervisor taking CPU time or
// memory back (steal time, a balloon, free page reporting).

#include "calibrate/device_limits.hpp"

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
  std::string lru_gen;  ///< /sys/kernel/mm/lru_gen/enabled as read, e.g. 0x0007 (empty: absent, no multi-generation LRU)
  // /proc/sys/vm: a ratio is 0 when its _bytes setting is used instead.
  double dirty_ratio = 0.2;
  double dirty_background_ratio = 0.1;
  std::int64_t dirty_bytes = 0;
  std::int64_t dirty_background_bytes = 0;
  double dirty_expire = 30.0;        ///< seconds (dirty_expire_centisecs)
  double writeback_interval = 5.0;   ///< seconds (dirty_writeback_centisecs)
  std::string file_system;           ///< of the folder measured in (statfs type, e.g. ext4)
  std::int64_t file_system_free = 0; ///< bytes an ordinary user may still write there
  DeviceLimits device;               ///< the kernel's readahead and largest request for that file system
  bool memory_limited = false;       ///< this process is in a memory cgroup with a limit
  /// A virtio balloon with VIRTIO_BALLOON_F_REPORTING: pages the guest frees go back to the
  /// host, which must fault them in again when they are next touched.
  bool free_page_reporting = false;
  bool balloon_device = false;       ///< a virtio balloon: the host may take memory back
};

/// CPU time since boot, from /proc/stat's "cpu" line, in seconds summed over every CPU.
struct CpuTimes {
  double busy = 0.0;   ///< user, nice, system, irq, softirq
  double steal = 0.0;  ///< taken by the hypervisor for others while this guest wanted to run
  double total = 0.0;  ///< everything, idle and iowait too
};

/// What happened on the machine between two moments, apart from this process.
struct Activity {
  double seconds = 0.0;
  double others_busy_cores = 0.0;  ///< CPUs kept busy by other processes and the kernel's own threads
  double steal_pct = 0.0;          ///< of the CPUs' time, taken by the hypervisor
  std::int64_t reported = -1;      ///< bytes of free memory reported to the host (-1: the kernel does not count them)
  std::int64_t memory_total_change = 0;  ///< MemTotal's change (a balloon inflating or deflating)
};

/// A point to measure Activity from.
class ActivityMark {
 public:
  ActivityMark();
  /// Since this mark was made.
  Activity since() const;

 private:
  double wall_;
  CpuTimes cpu_;
  double own_;
  std::int64_t reported_;
  std::int64_t memory_total_;
};

/// /proc/meminfo now.
std::string read_meminfo();
/// A /proc/meminfo field now, in bytes; -1 if absent.
std::int64_t meminfo_now(std::string_view key);

/// This process's group ("/a/b", "/" at the root) in the cgroup hierarchy whose
/// /proc/self/cgroup line has `prefix` after the hierarchy's id ("::" for v2, ":memory:" for
/// v1's memory controller); empty if there is none.
std::string own_cgroup(std::string_view prefix);

/// Bytes of free memory the kernel has reported to a virtual machine's host since boot, where
/// it counts them (a page_reporting module with a `reported_kib` parameter); -1 otherwise.
std::int64_t reported_free_bytes();

/// Reads it now, for measurements in `dir`.
SystemInfo read_system_info(const std::filesystem::path& dir);

// The parsers, apart for tests.
/// A /proc/meminfo field in bytes ("MemTotal:  24633100 kB" -> 25224294400); -1 if absent.
std::int64_t meminfo_bytes(std::string_view meminfo, std::string_view key);
/// The bracketed word of a sysfs choice ("always [madvise] never" -> "madvise").
std::string selected_choice(std::string_view text);
/// Whether /sys/kernel/mm/lru_gen/enabled's capability mask has its main switch (0x0001,
/// LRU_GEN_CORE; mm/vmscan.c, enabled_show): the kernel reclaims by generations.
bool lru_gen_enabled(std::string_view enabled);
/// The first "model name" of /proc/cpuinfo, and whether its flags name a hypervisor.
std::string cpuinfo_model(std::string_view cpuinfo);
bool cpuinfo_hypervisor(std::string_view cpuinfo);
/// /proc/stat's first line, in ticks of `ticks_per_second`.
CpuTimes proc_stat_cpu(std::string_view stat, double ticks_per_second);
/// A virtio device's sysfs `device` and `features`: a balloon (device id 5), and whether it
/// offers free page reporting (feature bit 5, VIRTIO_BALLOON_F_REPORTING; `features` is one
/// character per bit, bit 0 first).
bool virtio_balloon(std::string_view device);
bool virtio_balloon_reporting(std::string_view device, std::string_view features);

}  // namespace pagecache::calibrate
