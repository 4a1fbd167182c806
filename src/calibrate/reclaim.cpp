#include "calibrate/reclaim.hpp"

#include "calibrate/measure.hpp"
#include "calibrate/system_info.hpp"
#include "calibrate/text.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

namespace pagecache::calibrate {

namespace {

Figure not_measured(std::string why) { return Figure{0.0, "not measured: " + std::move(why), false}; }

}  // namespace

Figure reclaimed_write(const Calibration& c, const Scratch& scratch, const ReclaimSetting& setting) {
  const SystemInfo& sys = c.system;
  // Clean cache first, large enough that writing the target stays under the freerun ceiling
  // of the dirty limits (the fill is dirtyable memory); then memory held, step by step, until
  // free memory is just above the kernel's watermarks (min_free_kbytes), so that the write
  // must take most of its pages from the clean cache.
  const std::int64_t target = setting.target;
  const double freerun = sys.dirty_bytes > 0 ? 0.0 : (sys.dirty_ratio + sys.dirty_background_ratio) / 2.0;
  const std::int64_t fill = freerun > 0.0 ? static_cast<std::int64_t>(static_cast<double>(target) / freerun * 1.5) : 4 * target;
  const std::int64_t available = meminfo_now("MemAvailable");
  const std::int64_t floor = 2 * sys.min_free + 64 * MiB;  // stop holding here
  if (sys.file_system_free < setting.room + fill || available < fill + target + floor + 512 * MiB) {
    return not_measured("too little memory or disk to fill the cache");
  }
  // The fill goes at writeback's rate, the hold at first touch's: a machine with much memory
  // (or slow first touches) would take minutes.
  const double fill_rate = c.writeback.measured ? c.writeback.value : 100e6;
  // The hold takes memory long free: on a virtual machine with free page reporting, at the rate
  // into memory the host took back.
  const double touch_rate = c.memory_write_cold.measured ? c.memory_write_cold.value : c.first_touch.measured ? c.first_touch.value : 500e6;
  const double estimate = static_cast<double>(fill) / fill_rate + static_cast<double>(std::max<std::int64_t>(0, available - fill - floor)) / touch_rate;
  if (estimate > setting.budget) {
    return not_measured(fmt::format("filling {} of memory would take about {:.0f} s here (first touch at {:.0f} MB/s), over the {:.0f} s "
                                    "allowed",
                                    size_text(available), estimate, touch_rate / 1e6, setting.budget));
  }
  const std::filesystem::path filled = scratch.file("fill");
  const std::filesystem::path after = scratch.file("after");
  buffered_write_synced(filled, fill, setting.chunk, Deadline(setting.budget));  // clean cache
  Figure result;
  {
    MemoryHold hold(sys.page_size);
    // Never more than what was available less the write and a margin: the hold may push out
    // clean cache (the fill's too), never more.
    const std::int64_t most = available - target - 512 * MiB;
    for (std::int64_t free = meminfo_now("MemFree"); free > floor + 64 * MiB && hold.bytes() < most && !stop_requested();
         free = meminfo_now("MemFree")) {
      hold.add(std::min({free - floor, most - hold.bytes(), GiB}));
    }
    if (stop_requested()) throw std::runtime_error("interrupted: the files made so far are removed");
    const std::int64_t free_before = meminfo_now("MemFree");
    const Rate r = cache_write(after, target, setting.chunk, Deadline(30.0));
    const std::int64_t free_after = meminfo_now("MemFree");
    const std::int64_t from_free = std::clamp<std::int64_t>(free_before - free_after, 0, r.bytes);
    const std::int64_t reclaimed = r.bytes - from_free;
    const double free_seconds = c.memory_write.measured ? static_cast<double>(from_free) / c.memory_write.value : 0.0;
    if (reclaimed < r.bytes / 4) {
      result = not_measured(fmt::format("only {} of {} written needed reclaim ({} free before, {} after)", size_text(reclaimed), size_text(r.bytes),
                                        size_text(free_before), size_text(free_after)));
    } else if (r.seconds - free_seconds < r.seconds / 4) {
      // The part into free pages took nearly all the time: the rest is too short to time.
      result = not_measured(fmt::format("{} in {:.2f} s, of which {:.2f} s the part into free pages at memory_write_bw: too little left to time",
                                        size_text(r.bytes), r.seconds, free_seconds));
    } else {
      result = Figure{static_cast<double>(reclaimed) / (r.seconds - free_seconds),
                      fmt::format("write() into the page cache with {} clean cached and {} free: {} of it into reclaimed pages ({} in {:.2f} s, the "
                                  "part into free pages taken at memory_write_bw)",
                                  size_text(fill), size_text(free_before), size_text(reclaimed), size_text(r.bytes), r.seconds),
                      true};
    }
  }
  sync_and_drop(after);
  sync_and_drop(filled);
  scratch.remove(after);
  scratch.remove(filled);
  return result;
}

}  // namespace pagecache::calibrate
