// The platform file calibrate writes: one host with one disk, every value commented with its measurement.
#include "calibrate/calibrate.hpp"

#include "calibrate/text.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace pagecache::calibrate {

namespace {

std::string rate_toml(const char* key, const Figure& f) {
  if (!f.measured) return fmt::format("# {} not set: {}\n", key, f.how);
  return fmt::format("# {}\n{} = \"{}\"\n", f.how, key, rate_text(f.value));
}

// Streams together no faster than one (a disk that serves one stream at a time, or noise):
// pcsim takes the aggregate as one stream's, which it may not be below.
std::string aggregate_toml(const char* key, const Figure& together, const Figure& one) {
  if (!together.measured || !one.measured || together.value >= one.value) return rate_toml(key, together);
  Figure taken = one;
  taken.how = fmt::format("{}: {}, under one stream's; taken as one stream's", together.how, rate_text(together.value));
  return rate_toml(key, taken);
}

std::string for_comparison(const Figure& f) {
  if (!f.measured) return "";
  return fmt::format("# for comparison: {}: {}\n", f.how, rate_text(f.value));
}

// When, where and with what else running the figures were measured, and the notes.
std::string header_comments(const Calibration& c) {
  const SystemInfo& s = c.system;
  std::string out = fmt::format("# Measured by `pcsim calibrate` on {} ({:.0f} s{}).\n", c.date, c.seconds, c.quick ? ", --quick: rough" : "");
  out += fmt::format("# Machine: {}, {} {}, {} cores, {} of memory, Linux {}{}.\n", s.hostname, s.cpu_model.empty() ? "CPU" : s.cpu_model,
                     s.hypervisor ? "(virtual machine)" : "", s.cores, size_text(s.memory_total), s.kernel, s.root ? "" : ", not root");
  out += fmt::format("# Device: the file system of the folder measured in ({}), files of {}, {} streams at once.\n", s.file_system, size_text(c.size),
                     c.streams);
  out += fmt::format("# Other activity: {:.2f} cores busy outside calibrate before it measured, {:.2f} while it measured; steal {:.1f} % and "
                     "{:.1f} %{}.\n",
                     c.before.others_busy_cores, c.during.others_busy_cores, c.before.steal_pct, c.during.steal_pct,
                     c.during.reported >= 0 ? fmt::format("; {} of free memory reported to the host while measuring", size_text(c.during.reported)) : "");
  for (const std::string& note : c.notes) out += fmt::format("# Note: {}\n", note);
  return out;
}

std::string host_toml(const Calibration& c) {
  const SystemInfo& s = c.system;
  std::string out = fmt::format("\n[[hosts]]\nname = \"{}\"\n", s.hostname);
  out += fmt::format("# processors online\ncores = {}\n", s.cores);
  out += fmt::format("# /proc/meminfo MemTotal\nmemory = \"{} MiB\"\n", s.memory_total / MiB);
  out += fmt::format("# MemTotal - MemAvailable when measured: what the page cache could not have\nmemory_in_use = \"{} MiB\"\n",
                     (s.memory_total - s.memory_available) / MiB);
  out += rate_toml("memory_read_bw", c.memory_read);
  out += rate_toml("memory_write_bw", c.memory_write);
  out += rate_toml("memory_aggregate_read_bw", c.memory_aggregate_read);
  out += rate_toml("memory_aggregate_write_bw", c.memory_aggregate_write);
  out += rate_toml("memory_first_touch_bw", c.first_touch);
  out += rate_toml("memory_reclaimed_write_bw", c.memory_reclaimed_write);
  out += cold_fault_toml(c.cold_fault, c.memory_write, c.memory_write_cold);
  for (const Figure* f : {&c.memory_write_cold, &c.memory_read_fresh, &c.copy_one, &c.copy_all}) out += for_comparison(*f);
  return out;
}

// The kernel's dirty-page settings, as read.
std::string page_cache_toml(const SystemInfo& s) {
  std::string out = "\n[hosts.page_cache]\n";
  if (s.dirty_bytes > 0 || s.dirty_background_bytes > 0) {
    out += fmt::format("# /proc/sys/vm/dirty_bytes {} and dirty_background_bytes {}: as fractions of MemTotal\n", s.dirty_bytes,
                       s.dirty_background_bytes);
  } else {
    out += "# /proc/sys/vm/dirty_ratio and dirty_background_ratio\n";
  }
  const double total = static_cast<double>(std::max<std::int64_t>(s.memory_total, 1));
  const double ratio = s.dirty_bytes > 0 ? static_cast<double>(s.dirty_bytes) / total : s.dirty_ratio;
  const double background = s.dirty_background_bytes > 0 ? static_cast<double>(s.dirty_background_bytes) / total : s.dirty_background_ratio;
  out += fmt::format("dirty_ratio = {:.4g}\ndirty_background_ratio = {:.4g}\n", ratio, background);
  out += fmt::format("# dirty_expire_centisecs, dirty_writeback_centisecs\ndirty_expire = \"{:g} s\"\nwriteback_interval = \"{:g} s\"\n", s.dirty_expire,
                     s.writeback_interval);
  if (lru_gen_enabled(s.lru_gen)) {
    out += fmt::format("# /sys/kernel/mm/lru_gen/enabled {}: the kernel reclaims by generations\npolicy = \"mglru\"\n", s.lru_gen);
  } else {
    out += fmt::format("# /sys/kernel/mm/lru_gen/enabled {}: the two-list LRU, the profile's policy\n", s.lru_gen.empty() ? "absent" : s.lru_gen);
  }
  return out;
}

// What the kernel says of the device, read, not measured.
std::string device_limits_toml(const DeviceLimits& d) {
  std::string out;
  const std::string device = d.device.empty() ? "" : fmt::format(" ({})", d.device);
  if (d.read_ahead < 0) {
    out += fmt::format("# read_ahead not set: {}\n", d.read_ahead_from);
  } else {
    out += fmt::format("# the kernel's readahead window for this file system, read, not measured: {}{}\nread_ahead = \"{} KiB\"\n", d.read_ahead_from,
                       device, d.read_ahead / 1024);
  }
  if (d.max_request < 0) {
    out += fmt::format("# max_request not set: {}\n", d.max_request_from);
  } else {
    out += fmt::format("# the largest request the block layer sends the device, read, not measured: {}{}\nmax_request = \"{} KiB\"\n",
                       d.max_request_from, device, d.max_request / 1024);
  }
  return out;
}

std::string disk_toml(const Calibration& c) {
  std::string out = "\n[[hosts.disks]]\nname = \"disk\"\n";
  out += rate_toml("read_bw", c.disk_read);
  out += rate_toml("write_bw", c.writeback);
  out += aggregate_toml("aggregate_read_bw", c.disk_aggregate_read, c.disk_read);
  out += aggregate_toml("aggregate_write_bw", c.aggregate_writeback, c.writeback);
  out += request_latency_toml(c.request_rates, c.request_fit, c.size);
  out += device_limits_toml(c.system.device);
  out += write_cache_toml(c.write_cache, c.writeback.measured ? c.writeback.value : 0.0);
  for (const Figure* f : {&c.buffered_read, &c.buffered_read_cold, &c.disk_write, &c.disk_aggregate_write}) out += for_comparison(*f);
  return out;
}

}  // namespace

std::string platform_toml(const Calibration& c) {
  return header_comments(c) + host_toml(c) + page_cache_toml(c.system) + numa_toml(c.numa) + disk_toml(c);
}

}  // namespace pagecache::calibrate
