// The notes calibrate adds to its figures once everything is measured (notes.hpp).
#include "calibrate/notes.hpp"

#include "calibrate/text.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <utility>

namespace pagecache::calibrate {

namespace {

// What the machine did apart from calibrate, and what a hypervisor does with its memory.
std::vector<std::string> activity_notes(const Calibration& c) {
  std::vector<std::string> notes;
  const SystemInfo& s = c.system;
  if (c.before.others_busy_cores > 0.2) {
    notes.push_back(fmt::format("before measuring, other work kept {:.2f} of the {} cores busy: the figures share the machine with it",
                                c.before.others_busy_cores, s.cores));
  }
  if (c.during.others_busy_cores > 0.2) {
    notes.push_back(fmt::format("while measuring, {:.2f} cores were busy outside calibrate (other processes, or the kernel's own threads: "
                                "writeback, reclaim)",
                                c.during.others_busy_cores));
  }
  const double steal = std::max(c.before.steal_pct, c.during.steal_pct);
  if (steal > 2.0) {
    notes.push_back(fmt::format("the hypervisor took {:.1f} % of the CPUs' time (steal): other guests compete for its cores", steal));
  }
  if (s.hypervisor) {
    notes.push_back("a virtual machine: the device rates may be the host's cache rather than its disk, and speeds may change with what the "
                    "host does");
  }
  if (s.free_page_reporting) {
    std::string reported;
    if (c.during.reported > 0) reported = fmt::format(" ({} reported while measuring)", size_text(c.during.reported));
    std::string cold;
    if (c.memory_write_cold.measured && c.memory_write.measured) {
      cold = fmt::format(": a write into memory the host took back went at {}, into memory just freed at {} (memory_write_bw, what a task "
                         "reusing freed memory gets){}",
                         rate_text(c.memory_write_cold.value), rate_text(c.memory_write.value),
                         c.cold_fault.known ? "; memory_cold_fault_bw gives pcsim the difference" : "; pcsim has one rate for both");
    }
    notes.push_back(fmt::format("free page reporting is on (a virtio balloon): memory this machine frees goes back to the host{} a few seconds "
                                "later, and its next first touch waits for the host to give it again{}",
                                reported, cold));
  } else if (s.balloon_device) {
    notes.push_back("a virtio balloon: the host can take memory back while this runs");
  }
  if (c.during.memory_total_change != 0) {
    notes.push_back(fmt::format("MemTotal changed by {} MiB while measuring: a balloon took or gave memory", c.during.memory_total_change / MiB));
  }
  return notes;
}

// Platform figures whose repetitions disagree by more than a fifth.
void add_spread_notes(Calibration& c) {
  for (const auto& [key, f] : {std::pair<const char*, const Figure*>{"read_bw", &c.disk_read}, {"write_bw", &c.writeback},
                               {"aggregate_read_bw", &c.disk_aggregate_read}, {"aggregate_write_bw", &c.aggregate_writeback},
                               {"memory_read_bw", &c.memory_read}, {"memory_write_bw", &c.memory_write},
                               {"memory_aggregate_read_bw", &c.memory_aggregate_read}, {"memory_aggregate_write_bw", &c.memory_aggregate_write},
                               {"memory_first_touch_bw", &c.first_touch}}) {
    if (f->measured && f->spread_pct > 20.0) {
      c.notes.push_back(fmt::format("{} varied by {:.0f} % between its measurements: a noisy machine (other load), or memory or a device whose "
                                    "speed depends on its history (a virtual machine's host); pcsim takes the median",
                                    key, f->spread_pct));
    }
  }
}

// A read faster than most disks, or writeback faster than O_DIRECT writes: a cache below the file system.
void add_device_notes(Calibration& c) {
  if (c.disk_read.measured && c.disk_read.value > 8e9) {
    c.notes.push_back(fmt::format("the device read at {}: faster than most disks; a cache below the file system may have served it",
                                  rate_text(c.disk_read.value)));
  }
  if (c.writeback.measured && c.disk_write.measured && c.writeback.value > 1.25 * c.disk_write.value) {
    c.notes.push_back(fmt::format("writeback drained at {}, O_DIRECT writes went at {}: a write cache below the file system (a virtual "
                                  "machine's host, a controller) absorbs written data; write_bw is writeback's, which applications writing "
                                  "through the page cache get while that cache has room",
                                  rate_text(c.writeback.value), rate_text(c.disk_write.value)));
  }
}

// write_bw against the rate the device sustains once its own write cache is full.
void add_write_cache_note(Calibration& c) {
  if (c.write_cache.measured && !c.write_cache.setting.quick && c.writeback.measured) {
    const WriteCacheFinding& f = c.write_cache.finding;
    const bool above = c.writeback.value > f.sustained;
    if (f.fell) {
      c.notes.push_back(fmt::format("write_bw (writeback, {}) is {} sustained_write_bw ({}), the device's rate once its write cache is full "
                                    "(after {} of O_DIRECT writes){}",
                                    rate_text(c.writeback.value), above ? "above" : "not above", rate_text(f.sustained),
                                    size_text(f.cache_bytes), above ? ": writing back more than that cache holds goes slower than write_bw" : ""));
    } else {
      std::int64_t bytes = 0;
      for (const Rate& r : c.write_cache.pieces) bytes += r.bytes;
      c.notes.push_back(fmt::format("write_bw (writeback, {}) is {} the rate O_DIRECT writes sustained over {} ({}, no write cache found)",
                                    rate_text(c.writeback.value), above ? "above" : "not above", size_text(bytes), rate_text(f.sustained)));
    }
  }
}

}  // namespace

void add_notes(Calibration& c) {
  add_spread_notes(c);
  for (std::string& note : activity_notes(c)) c.notes.push_back(std::move(note));
  if (!c.system.root) {
    c.notes.push_back("not root: the whole page cache could not be dropped; each measuring file was dropped by itself (POSIX_FADV_DONTNEED), "
                      "which needs no root");
  }
  add_device_notes(c);
  add_write_cache_note(c);
  for (std::string& note : numa_notes(c.numa)) c.notes.push_back(std::move(note));
}

}  // namespace pagecache::calibrate
