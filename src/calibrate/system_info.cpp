#include "calibrate/system_info.hpp"

#include <algorithm>
#include <chrono>
#include <fstream>
#include <sstream>
#include <cstdlib>
#include <string>
#include <tuple>
#include <utility>

#include <sys/resource.h>
#include <sys/statfs.h>
#include <sys/statvfs.h>
#include <sys/utsname.h>
#include <unistd.h>

namespace pagecache::calibrate {

namespace {

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::ostringstream out;
  out << in.rdbuf();
  return out.str();
}

// A number in a /proc/sys file, or `fallback` if it cannot be read.
std::int64_t read_number(const std::filesystem::path& path, std::int64_t fallback) {
  std::ifstream in(path);
  std::int64_t value = 0;
  return in >> value ? value : fallback;
}

std::string trim(std::string_view s) {
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string_view::npos) return {};
  const auto last = s.find_last_not_of(" \t\r\n");
  return std::string(s.substr(first, last - first + 1));
}

std::string file_system_name(long type) {
  switch (static_cast<unsigned long>(type)) {
    case 0xEF53: return "ext2/3/4";
    case 0x58465342: return "xfs";
    case 0x9123683E: return "btrfs";
    case 0x01021994: return "tmpfs";
    case 0x6969: return "nfs";
    case 0x794C7630: return "overlayfs";
    case 0x2FC12FC1: return "zfs";
    case 0x65735546: return "fuse";
    default: return "unknown";
  }
}

// Whether this process's memory cgroup has a limit: cgroup v2's memory.max other than "max",
// or v1's memory.limit_in_bytes below "unlimited" (a page-rounded 2^63 - 1).
bool in_limited_memory_cgroup() {
  if (const std::string v2 = own_cgroup("::"); !v2.empty()) {
    const std::string max = trim(read_text(std::filesystem::path("/sys/fs/cgroup") / v2.substr(1) / "memory.max"));
    if (!max.empty() && max != "max") return true;
  }
  if (const std::string v1 = own_cgroup(":memory:"); !v1.empty()) {
    const std::int64_t limit = read_number(std::filesystem::path("/sys/fs/cgroup/memory") / v1.substr(1) / "memory.limit_in_bytes", -1);
    if (limit > 0 && limit < (std::int64_t{1} << 62)) return true;
  }
  return false;
}

// Whether any virtio device is a balloon, and whether one offers free page reporting.
std::pair<bool, bool> find_balloon() {
  bool balloon = false;
  bool reporting = false;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator("/sys/bus/virtio/devices", ec)) {
    const std::string device = read_text(entry.path() / "device");
    balloon = balloon || virtio_balloon(device);
    reporting = reporting || virtio_balloon_reporting(device, read_text(entry.path() / "features"));
  }
  return {balloon, reporting};
}

double own_cpu_seconds() {
  rusage u{};
  ::getrusage(RUSAGE_SELF, &u);
  const auto seconds = [](const timeval& t) { return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_usec) * 1e-6; };
  return seconds(u.ru_utime) + seconds(u.ru_stime);
}

double wall_seconds() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

CpuTimes cpu_times_now() { return proc_stat_cpu(read_text("/proc/stat"), static_cast<double>(::sysconf(_SC_CLK_TCK))); }

}  // namespace

CpuTimes proc_stat_cpu(std::string_view stat, double ticks_per_second) {
  CpuTimes t;
  if (stat.substr(0, 4) != "cpu " || ticks_per_second <= 0.0) return t;
  std::istringstream in{std::string(stat.substr(4, stat.find('\n') - 4))};
  // user nice system idle iowait irq softirq steal (guest and guest_nice are within user and nice)
  double v[8] = {};
  for (double& x : v) {
    if (!(in >> x)) break;
  }
  t.busy = (v[0] + v[1] + v[2] + v[5] + v[6]) / ticks_per_second;
  t.steal = v[7] / ticks_per_second;
  t.total = (v[0] + v[1] + v[2] + v[3] + v[4] + v[5] + v[6] + v[7]) / ticks_per_second;
  return t;
}

bool virtio_balloon(std::string_view device) { return trim(device) == "0x0005"; }

bool virtio_balloon_reporting(std::string_view device, std::string_view features) {
  return virtio_balloon(device) && features.size() > 5 && features[5] == '1';
}

ActivityMark::ActivityMark()
    : wall_(wall_seconds()), cpu_(cpu_times_now()), own_(own_cpu_seconds()), reported_(reported_free_bytes()),
      memory_total_(meminfo_bytes(read_meminfo(), "MemTotal")) {}

Activity ActivityMark::since() const {
  Activity a;
  const CpuTimes cpu = cpu_times_now();
  a.seconds = wall_seconds() - wall_;
  const double own = own_cpu_seconds() - own_;
  if (a.seconds > 0.0) a.others_busy_cores = std::max(0.0, (cpu.busy - cpu_.busy - own) / a.seconds);
  if (cpu.total > cpu_.total) a.steal_pct = (cpu.steal - cpu_.steal) / (cpu.total - cpu_.total) * 100.0;
  const std::int64_t reported = reported_free_bytes();
  if (reported_ >= 0 && reported >= reported_) a.reported = reported - reported_;
  a.memory_total_change = meminfo_bytes(read_meminfo(), "MemTotal") - memory_total_;
  return a;
}

std::string own_cgroup(std::string_view prefix) {
  const std::string self = read_text("/proc/self/cgroup");
  for (std::size_t at = 0; at < self.size();) {
    const std::size_t end = std::min(self.find('\n', at), self.size());
    const std::string_view line = std::string_view(self).substr(at, end - at);
    const auto colon = line.find(':');
    if (colon != std::string_view::npos && line.substr(colon).rfind(prefix, 0) == 0) {
      const std::string path = trim(line.substr(colon + prefix.size()));
      return path.empty() ? "/" : path;
    }
    at = end + 1;
  }
  return {};
}

std::int64_t reported_free_bytes() {
  const std::int64_t kib = read_number("/sys/module/page_reporting/parameters/reported_kib", -1);
  return kib < 0 ? -1 : kib * 1024;
}

std::string read_meminfo() { return read_text("/proc/meminfo"); }

std::int64_t meminfo_now(std::string_view key) { return meminfo_bytes(read_meminfo(), key); }

std::int64_t meminfo_bytes(std::string_view meminfo, std::string_view key) {
  std::size_t at = 0;
  while (at < meminfo.size()) {
    const std::size_t end = meminfo.find('\n', at);
    const std::string_view line = meminfo.substr(at, end == std::string_view::npos ? std::string_view::npos : end - at);
    if (line.size() > key.size() && line.substr(0, key.size()) == key && line[key.size()] == ':') {
      std::istringstream in{std::string(line.substr(key.size() + 1))};
      std::int64_t value = 0;
      std::string unit;
      if (!(in >> value)) return -1;
      in >> unit;
      return unit == "kB" ? value * 1024 : value;
    }
    if (end == std::string_view::npos) break;
    at = end + 1;
  }
  return -1;
}

std::string selected_choice(std::string_view text) {
  const auto open = text.find('[');
  const auto close = text.find(']', open);
  if (open == std::string_view::npos || close == std::string_view::npos) return trim(text);
  return std::string(text.substr(open + 1, close - open - 1));
}

bool lru_gen_enabled(std::string_view enabled) {
  const std::string text = trim(enabled);
  if (text.empty()) return false;
  const unsigned long mask = std::strtoul(text.c_str(), nullptr, 16);  // "0x0007"; strtoul takes the prefix
  return (mask & 0x1UL) != 0;
}

std::string cpuinfo_model(std::string_view cpuinfo) {
  const auto at = cpuinfo.find("model name");
  if (at == std::string_view::npos) return {};
  const auto colon = cpuinfo.find(':', at);
  const auto end = cpuinfo.find('\n', at);
  if (colon == std::string_view::npos || colon > end) return {};
  return trim(cpuinfo.substr(colon + 1, end - colon - 1));
}

bool cpuinfo_hypervisor(std::string_view cpuinfo) {
  const auto at = cpuinfo.find("\nflags");
  if (at == std::string_view::npos) return false;
  const std::string_view line = cpuinfo.substr(at, cpuinfo.find('\n', at + 1) - at);
  return line.find(" hypervisor") != std::string_view::npos;
}

SystemInfo read_system_info(const std::filesystem::path& dir) {
  SystemInfo s;
  char host[256] = {};
  if (::gethostname(host, sizeof host - 1) == 0) s.hostname = host;
  if (s.hostname.empty()) s.hostname = "host";
  utsname u{};
  if (::uname(&u) == 0) s.kernel = u.release;
  const std::string cpuinfo = read_text("/proc/cpuinfo");
  s.cpu_model = cpuinfo_model(cpuinfo);
  s.hypervisor = cpuinfo_hypervisor(cpuinfo);
  s.cores = static_cast<int>(std::max<long>(1, ::sysconf(_SC_NPROCESSORS_ONLN)));
  s.root = ::geteuid() == 0;
  const std::string meminfo = read_meminfo();
  s.memory_total = meminfo_bytes(meminfo, "MemTotal");
  s.memory_available = meminfo_bytes(meminfo, "MemAvailable");
  s.memory_free = meminfo_bytes(meminfo, "MemFree");
  s.page_size = ::sysconf(_SC_PAGESIZE);
  s.transparent_hugepages = selected_choice(read_text("/sys/kernel/mm/transparent_hugepage/enabled"));
  s.lru_gen = trim(read_text("/sys/kernel/mm/lru_gen/enabled"));
  const std::filesystem::path vm = "/proc/sys/vm";
  s.min_free = read_number(vm / "min_free_kbytes", 0) * 1024;
  s.dirty_ratio = static_cast<double>(read_number(vm / "dirty_ratio", 20)) / 100.0;
  s.dirty_background_ratio = static_cast<double>(read_number(vm / "dirty_background_ratio", 10)) / 100.0;
  s.dirty_bytes = read_number(vm / "dirty_bytes", 0);
  s.dirty_background_bytes = read_number(vm / "dirty_background_bytes", 0);
  s.dirty_expire = static_cast<double>(read_number(vm / "dirty_expire_centisecs", 3000)) / 100.0;
  s.writeback_interval = static_cast<double>(read_number(vm / "dirty_writeback_centisecs", 500)) / 100.0;
  struct statfs fs{};
  if (::statfs(dir.c_str(), &fs) == 0) s.file_system = file_system_name(fs.f_type);
  struct statvfs vfs{};
  if (::statvfs(dir.c_str(), &vfs) == 0) s.file_system_free = static_cast<std::int64_t>(vfs.f_bavail) * static_cast<std::int64_t>(vfs.f_frsize);
  s.device = device_limits_of(dir);
  s.memory_limited = in_limited_memory_cgroup();
  std::tie(s.balloon_device, s.free_page_reporting) = find_balloon();
  return s;
}

}  // namespace pagecache::calibrate
